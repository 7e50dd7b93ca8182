#!/usr/bin/env bash
# isa_symbols_test.sh LIBACCELVIZ_CORE.a: every global or weak symbol defined by the AVX2 and
# AVX-512 units (wide_bvh_avx2.cpp.o, wide_bvh_avx512.cpp.o) must name its instruction set
# (the Avx2Tag / Avx512Tag template argument or the _avx2 / _avx512 suffix). A weak copy of
# a shared inline function (a std::vector member, a header helper) compiled with AVX
# instructions could otherwise be the one the linker keeps for the SSE2 path, and crash an
# older CPU. Also: neither unit may contain a fused multiply-add (vfmadd..., vfmsub...,
# vfnmadd..., vfnmsub...): it would round the slab or triangle test differently from the
# SSE2 kernel and can break the slab test's conservative bound (-ffp-contract=off).
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
  # DW.ref.__gxx_personality_v0 is the exception-handling personality pointer every C++
  # object file may carry: data, the same in all of them.
  bad="$(grep -vi "$isa" <<<"$syms" | grep -v ' DW\.ref\.__gxx_personality_v0$' || true)"
  if [[ -n "$bad" ]]; then
    echo "isa_symbols: $member defines symbols without '$isa' in their name:" >&2
    echo "$bad" >&2
    status=1
  else
    echo "isa_symbols: $member: $(wc -l <<<"$syms") symbols, all named for $isa"
  fi
  fused="$(objdump -d "$lib" 2>/dev/null | awk -v m="$member:" '
      /file format/ {cur = $1; next} cur == m && /vf(n)?m(add|sub)/ {n++} END {print n + 0}')"
  if [[ "$fused" != 0 ]]; then
    echo "isa_symbols: $member contains $fused fused multiply-add instructions" >&2
    status=1
  fi
done
exit $status
