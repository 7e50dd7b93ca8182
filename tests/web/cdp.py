"""A small Chrome DevTools Protocol client over --remote-debugging-pipe (standard library only).

    with Browser() as browser:
        page = browser.new_page()
        page.navigate('http://127.0.0.1:8000/accelviz.html')
        page.wait_for_console('accelviz: ready', timeout=60)
        print(page.evaluate('1 + 1'))

The browser reads NUL-terminated JSON messages on its fd 3 and writes them on its fd 4. A
reader thread dispatches replies (by id) and events (by sessionId) to the Browser and its Pages.
Every wait has a timeout and raises CdpError (or WaitTimeout) naming what it waited for and
the page's last console lines. Browser.close() kills the whole process group and removes the
temporary profile; it also runs on exceptions when Browser is used as a context manager.
"""

import base64
import fcntl
import json
import os
import shutil
import signal
import subprocess
import tempfile
import threading
import time

CHROMIUM_FLAGS = [
    '--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
    '--remote-debugging-pipe', '--no-first-run', '--no-default-browser-check',
    '--disable-gpu-sandbox', '--disable-background-timer-throttling',
    '--disable-renderer-backgrounding', '--disable-backgrounding-occluded-windows',
    '--disable-extensions', '--mute-audio',
]

# key -> (code, windowsVirtualKeyCode, text typed or None)
_KEYS = {
    'PageDown': ('PageDown', 34, None), 'PageUp': ('PageUp', 33, None),
    'End': ('End', 35, None), 'Home': ('Home', 36, None),
    'ArrowLeft': ('ArrowLeft', 37, None), 'ArrowUp': ('ArrowUp', 38, None),
    'ArrowRight': ('ArrowRight', 39, None), 'ArrowDown': ('ArrowDown', 40, None),
    'Enter': ('Enter', 13, '\r'), 'Escape': ('Escape', 27, None), 'Tab': ('Tab', 9, None),
    'Backspace': ('Backspace', 8, None), 'Delete': ('Delete', 46, None),
    ' ': ('Space', 32, ' '), 'Space': ('Space', 32, ' '),
}
for _i in range(1, 13):
    _KEYS['F%d' % _i] = ('F%d' % _i, 111 + _i, None)
for _c in 'abcdefghijklmnopqrstuvwxyz':
    _KEYS[_c] = ('Key' + _c.upper(), ord(_c.upper()), _c)
for _c in '0123456789':
    _KEYS[_c] = ('Digit' + _c, ord(_c), _c)


class CdpError(Exception):
    """A protocol error, a dead browser, or a wait that ran out of time."""


class WaitTimeout(CdpError):
    pass


class JsError(CdpError):
    """Runtime.evaluate threw."""


def find_chromium():
    for name in (os.environ.get('CHROMIUM'), 'chromium', 'chromium-browser', 'google-chrome',
                 'google-chrome-stable', 'chrome'):
        if name:
            path = shutil.which(name)
            if path:
                return path
    return None


def _remote_object_text(obj):
    if 'value' in obj:
        value = obj['value']
        if isinstance(value, str):
            return value
        return json.dumps(value)
    if 'unserializableValue' in obj:
        return obj['unserializableValue']
    if 'description' in obj:
        return obj['description']
    return obj.get('type', '?')


class Browser:
    def __init__(self, executable=None, extra_args=(), stderr_path=None):
        self.executable = executable or find_chromium()
        if not self.executable:
            raise CdpError('chromium not found (set CHROMIUM=/path/to/chromium)')
        self.extra_args = list(extra_args)
        self.stderr_path = stderr_path  # None: discard chromium's (noisy) stderr
        self.proc = None
        self.profile = None
        self._to_browser = None  # our write end (the browser's fd 3)
        self._from_browser = None  # our read end (the browser's fd 4)
        self._write_lock = threading.Lock()
        self._cond = threading.Condition()
        self._next_id = 0
        self._replies = {}
        self._pages = {}  # sessionId -> Page
        self._events = []  # browser-level events (no sessionId)
        self._dead = None  # reason the connection ended
        self._reader = None

    # ---- lifetime
    def __enter__(self):
        self.launch()
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def launch(self):
        self.profile = tempfile.mkdtemp(prefix='accelviz-chromium-')
        child_in_r, parent_w = os.pipe()  # we write, the browser reads (its fd 3)
        parent_r, child_out_w = os.pipe()  # the browser writes (its fd 4), we read
        # Move the child's ends above 4 so that mapping them onto 3 and 4 cannot clash.
        for name in ('child_in_r', 'child_out_w'):
            fd = locals()[name]
            high = fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 10)
            os.close(fd)
            if name == 'child_in_r':
                child_in_r = high
            else:
                child_out_w = high
        stderr = subprocess.DEVNULL
        stderr_file = None
        try:
            if self.stderr_path:
                stderr_file = open(self.stderr_path, 'ab')
                stderr = stderr_file
            args = [self.executable] + CHROMIUM_FLAGS + self.extra_args + [
                '--user-data-dir=' + self.profile, 'about:blank']
            # bash maps the pipe ends onto fds 3 and 4 and execs chromium (same pid), which
            # avoids preexec_fn (unsafe with threads) and fd-number clashes.
            shell = 'exec "$0" "$@" 3<&%d 4>&%d %d<&- %d>&-' % (
                child_in_r, child_out_w, child_in_r, child_out_w)
            self.proc = subprocess.Popen(
                ['bash', '-c', shell] + args, stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL, stderr=stderr, pass_fds=(child_in_r, child_out_w),
                start_new_session=True)
        except BaseException:
            for fd in (child_in_r, child_out_w, parent_w, parent_r):
                os.close(fd)
            self._remove_profile()
            raise
        finally:
            if stderr_file:
                stderr_file.close()
        os.close(child_in_r)
        os.close(child_out_w)
        self._to_browser = parent_w
        self._from_browser = parent_r
        self._reader = threading.Thread(target=self._read_loop, name='cdp-reader', daemon=True)
        self._reader.start()
        try:
            self.send('Browser.getVersion', timeout=30)
        except BaseException:
            self.close()
            raise
        return self

    def close(self):
        proc, self.proc = self.proc, None
        if proc is not None:
            if self._dead is None:
                try:
                    self._send_nowait('Browser.close')
                except OSError:
                    pass
                try:
                    proc.wait(timeout=5)
                except subprocess.TimeoutExpired:
                    pass
            # The browser's helpers (zygote, GPU, renderers) share its process group.
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
            try:
                proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                pass
            # Wait (briefly) until the helpers are gone too, so the profile can be removed.
            deadline = time.monotonic() + 5
            while time.monotonic() < deadline:
                try:
                    os.killpg(proc.pid, 0)
                except (ProcessLookupError, PermissionError):
                    break
                time.sleep(0.1)
        for attr in ('_to_browser', '_from_browser'):
            fd = getattr(self, attr)
            if fd is not None:
                setattr(self, attr, None)
                try:
                    os.close(fd)
                except OSError:
                    pass
        if self._reader is not None and self._reader is not threading.current_thread():
            self._reader.join(timeout=5)
        self._remove_profile()

    def _remove_profile(self):
        if self.profile:
            # A helper may still be writing for a moment after the kill.
            for _ in range(5):
                shutil.rmtree(self.profile, ignore_errors=True)
                if not os.path.exists(self.profile):
                    break
                time.sleep(0.2)
            self.profile = None

    # ---- protocol
    def _read_loop(self):
        buf = b''
        reason = 'the browser closed the pipe'
        try:
            while True:
                fd = self._from_browser
                if fd is None:
                    break
                chunk = os.read(fd, 1 << 20)
                if not chunk:
                    break
                buf += chunk
                while True:
                    end = buf.find(b'\0')
                    if end < 0:
                        break
                    raw, buf = buf[:end], buf[end + 1:]
                    try:
                        msg = json.loads(raw.decode('utf-8', 'replace'))
                    except ValueError:
                        continue
                    self._dispatch(msg)
        except OSError as e:
            reason = 'reading from the browser failed: %s' % e
        with self._cond:
            self._dead = reason
            self._cond.notify_all()
        for page in list(self._pages.values()):
            page._on_dead(reason)

    def _dispatch(self, msg):
        if 'id' in msg:
            with self._cond:
                self._replies[msg['id']] = msg
                self._cond.notify_all()
            return
        session = msg.get('sessionId')
        if session:
            page = self._pages.get(session)
            if page:
                page._on_event(msg.get('method'), msg.get('params', {}))
            return
        with self._cond:
            self._events.append(msg)
            self._cond.notify_all()

    def _send_nowait(self, method, params=None, session_id=None):
        with self._cond:
            self._next_id += 1
            msg_id = self._next_id
        msg = {'id': msg_id, 'method': method, 'params': params or {}}
        if session_id:
            msg['sessionId'] = session_id
        data = json.dumps(msg).encode() + b'\0'
        with self._write_lock:
            fd = self._to_browser
            if fd is None:
                raise CdpError('the browser is closed')
            view = memoryview(data)
            while view:
                n = os.write(fd, view)
                view = view[n:]
        return msg_id

    def send(self, method, params=None, session_id=None, timeout=60, describe=None):
        """Sends a command and returns its result; raises CdpError on a protocol error."""
        if self._dead is not None:
            raise CdpError('%s: the browser is gone (%s)' % (method, self._dead))
        try:
            msg_id = self._send_nowait(method, params, session_id)
        except OSError as e:
            raise CdpError('%s: writing to the browser failed: %s' % (method, e))
        deadline = time.monotonic() + timeout
        with self._cond:
            while msg_id not in self._replies:
                if self._dead is not None:
                    raise CdpError('%s: the browser is gone (%s)' % (method, self._dead))
                left = deadline - time.monotonic()
                if left <= 0:
                    raise WaitTimeout('%s: no reply within %g s%s' % (
                        method, timeout, describe() if describe else ''))
                self._cond.wait(min(left, 1.0))
            reply = self._replies.pop(msg_id)
        if 'error' in reply:
            err = reply['error']
            raise CdpError('%s: %s %s' % (method, err.get('message'), err.get('data', '')))
        return reply.get('result', {})

    # ---- pages
    def new_page(self, width=None, height=None):
        """Opens a tab on about:blank, attached (flatten) with Runtime, Log and Page enabled."""
        target = self.send('Target.createTarget', {'url': 'about:blank'})['targetId']
        session = self.send('Target.attachToTarget',
                            {'targetId': target, 'flatten': True})['sessionId']
        page = Page(self, target, session)
        with self._cond:
            self._pages[session] = page
        page._enable()
        if width and height:
            page.set_viewport(width, height)
        return page


class Page:
    def __init__(self, browser, target_id, session_id):
        self.browser = browser
        self.target_id = target_id
        self.session_id = session_id
        self._cond = threading.Condition()
        self.console = []  # (level, text): Runtime.consoleAPICalled
        self.errors = []  # (source, text): console errors, exceptions, Log errors
        self.warnings = []  # (source, text): Log warnings (SwiftShader etc.), for debugging
        self.events = []  # (method, params) of the other events
        self.keep_events = False
        self.crashed = None
        self.closed = False

    # ---- events
    def _on_event(self, method, params):
        with self._cond:
            if method == 'Runtime.consoleAPICalled':
                level = params.get('type', 'log')
                text = ' '.join(_remote_object_text(a) for a in params.get('args', []))
                self.console.append((level, text))
                if level in ('error', 'assert'):
                    self.errors.append(('console.' + level, text))
            elif method == 'Runtime.exceptionThrown':
                details = params.get('exceptionDetails', {})
                self.errors.append(('exception', _exception_text(details)))
            elif method == 'Log.entryAdded':
                entry = params.get('entry', {})
                text = entry.get('text', '')
                if entry.get('url'):
                    text += ' (%s)' % entry['url']
                source = 'log.%s' % entry.get('source', '?')
                if entry.get('level') == 'error':
                    self.errors.append((source, text))
                elif entry.get('level') == 'warning':
                    self.warnings.append((source, text))
            elif method in ('Inspector.targetCrashed',):
                self.crashed = 'the page crashed'
                self.errors.append(('crash', 'the page crashed'))
            elif method == 'Inspector.detached':
                self.crashed = 'detached: %s' % params.get('reason')
            elif self.keep_events:
                self.events.append((method, params))
            self._cond.notify_all()

    def _on_dead(self, reason):
        with self._cond:
            self.crashed = self.crashed or reason
            self._cond.notify_all()

    def _enable(self):
        for method in ('Runtime.enable', 'Log.enable', 'Page.enable', 'Inspector.enable'):
            try:
                self.send(method)
            except CdpError:
                if method != 'Inspector.enable':
                    raise

    def send(self, method, params=None, timeout=60):
        return self.browser.send(method, params, self.session_id, timeout, self._describe)

    def close(self):
        if not self.closed:
            self.closed = True
            try:
                self.browser.send('Target.closeTarget', {'targetId': self.target_id}, timeout=10)
            except CdpError:
                pass
            self.browser._pages.pop(self.session_id, None)

    # ---- state for messages
    def console_lines(self):
        with self._cond:
            return [text for _, text in self.console]

    def mark(self):
        """The number of console lines so far: pass it as since= to wait only for newer ones."""
        with self._cond:
            return len(self.console)

    def last_console(self, n=20, width=300):
        with self._cond:
            lines = list(self.console[-n:])
            errors = list(self.errors[-n:])
        out = ['last %d console lines:' % len(lines)]
        out += ['  [%s] %s' % (lvl, _clip(text, width)) for lvl, text in lines] or ['  (none)']
        if errors:
            out.append('errors:')
            out += ['  [%s] %s' % (src, _clip(text, width)) for src, text in errors]
        return '\n'.join(out)

    def _describe(self):
        return '\n' + self.last_console()

    # ---- commands
    def navigate(self, url, timeout=60, clear=True):
        """Loads url. clear: forget the console lines and errors of the previous document."""
        if clear:
            with self._cond:
                self.console.clear()
                self.errors.clear()
                self.warnings.clear()
        result = self.send('Page.navigate', {'url': url}, timeout=timeout)
        if result.get('errorText'):
            raise CdpError('navigate %s: %s' % (url, result['errorText']))
        return result

    def wait_for_console(self, match, timeout=30, since=0, fail_on_error=False, what=None):
        """Waits for a console line (from index since on) that contains the substring match or
        for which the predicate match(text) is true, and returns its text. fail_on_error: stop
        early when the page reports an error: True for any error (console.error, Log error, uncaught
        exception), or a collection of sources, e.g. ('exception', 'crash'). what: how errors
        name the line."""
        pred = match if callable(match) else (lambda text: match in text)
        if what is None:
            what = repr(match) if not callable(match) else getattr(match, '__doc__', None) or \
                getattr(match, '__name__', 'matching')
        deadline = time.monotonic() + timeout
        index = since
        with self._cond:
            while True:
                while index < len(self.console):
                    text = self.console[index][1]
                    index += 1
                    if pred(text):
                        return text
                fatal = [e for e in self.errors if fail_on_error is True or
                         (fail_on_error and e[0] in fail_on_error)]
                if fatal:
                    src, text = fatal[0]
                    raise CdpError('waiting for console %s: page error [%s] %s\n%s' % (
                        what, src, _clip(text, 500), self.last_console()))
                if self.crashed:
                    raise CdpError('waiting for console %s: %s\n%s' % (
                        what, self.crashed, self.last_console()))
                left = deadline - time.monotonic()
                if left <= 0:
                    raise WaitTimeout('no console line %s within %g s\n%s' % (
                        what, timeout, self.last_console()))
                self._cond.wait(min(left, 1.0))

    def evaluate(self, js, await_promise=False, timeout=60):
        """Evaluates js in the page and returns its value (JSON-serialisable values)."""
        result = self.send('Runtime.evaluate', {
            'expression': js, 'returnByValue': True, 'awaitPromise': await_promise,
            'userGesture': True}, timeout=timeout)
        if 'exceptionDetails' in result:
            raise JsError('evaluate %s: %s' % (_clip(js, 200),
                                               _exception_text(result['exceptionDetails'])))
        obj = result.get('result', {})
        if 'value' in obj:
            return obj['value']
        if 'unserializableValue' in obj:
            return obj['unserializableValue']
        return None

    def press_key(self, key, modifiers=0):
        """keyDown + keyUp of a key by its DOM name: 'PageDown', 'F12', 'ArrowDown', 'a', ..."""
        if key not in _KEYS:
            raise ValueError('press_key: unknown key %r' % key)
        code, vk, text = _KEYS[key]
        dom_key = ' ' if key == 'Space' else key
        base = {'key': dom_key, 'code': code, 'windowsVirtualKeyCode': vk,
                'nativeVirtualKeyCode': vk, 'modifiers': modifiers}
        down = dict(base, type='keyDown' if text else 'rawKeyDown')
        if text:
            down.update(text=text, unmodifiedText=text)
        self.send('Input.dispatchKeyEvent', down)
        self.send('Input.dispatchKeyEvent', dict(base, type='keyUp'))

    def click(self, x, y, button='left'):
        buttons = {'left': 1, 'right': 2, 'middle': 4}[button]
        self.send('Input.dispatchMouseEvent', {'type': 'mouseMoved', 'x': x, 'y': y})
        self.send('Input.dispatchMouseEvent', {'type': 'mousePressed', 'x': x, 'y': y,
                                               'button': button, 'buttons': buttons,
                                               'clickCount': 1})
        self.send('Input.dispatchMouseEvent', {'type': 'mouseReleased', 'x': x, 'y': y,
                                               'button': button, 'buttons': 0,
                                               'clickCount': 1})

    def screenshot_png(self, timeout=60):
        data = self.send('Page.captureScreenshot', {'format': 'png'}, timeout=timeout)['data']
        return base64.b64decode(data)

    def set_viewport(self, width, height, scale=1):
        self.send('Emulation.setDeviceMetricsOverride', {
            'width': int(width), 'height': int(height), 'deviceScaleFactor': scale,
            'mobile': False})


def _exception_text(details):
    exc = details.get('exception') or {}
    text = exc.get('description') or details.get('text', 'exception')
    where = details.get('url') or ''
    if where:
        text += ' (%s:%s)' % (where, details.get('lineNumber', '?'))
    return text


def _clip(text, width):
    text = text.replace('\n', '\\n')
    return text if len(text) <= width else text[:width] + '... (%d chars)' % len(text)
