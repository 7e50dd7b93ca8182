#!/usr/bin/env bash
# isa_symbols_test.sh LIBACCELVIZ_CORE.a: every global or weak symbol defined by the AVX2 and
# AVX-512 units (wide_bvh_avx2.cpp.o, wide_bvh_avx512.cpp.o) must name its instruction set
# (the Avx2Tag / Avx512Tag template argument or the _avx2 / _avx512 suffix). A weak copy of
# a shared inline function (a std::vector member, a header helper) compiled with AVX
# instructions could otherwise be the one the linker keeps for the SSE2 path, and crash an
# older CPU.
set -euo pipefail
lib="$1"
status=0
for isa in avx2 avx512; do
  member="wide_bvh_${isa}.cpp.o"
  syms="$(nm -C --defined-only -g "$lib" 2>/dev/null | awk -v m="$member:" '
      /^$/ {next} /:$/ {cur = $0; next} cur == m {print}')"
  if [[ -z "$syms" ]]; then
    echo "isa_symbols: no symbols found for $member in $lib" >&2
    status=1
    continue
  fi
  bad="$(grep -vi "$isa" <<<"$syms" || true)"
  if [[ -n "$bad" ]]; then
    echo "isa_symbols: $member defines symbols without '$isa' in their name:" >&2
    echo "$bad" >&2
    status=1
  else
    echo "isa_symbols: $member: $(wc -l <<<"$syms") symbols, all named for $isa"
  fi
done
exit $status
