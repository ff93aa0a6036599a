"""The socket server of nervous (seed 003 §6.3.3, App. C.2.2): many clients, one line in, one line out.

§6.3.3: "nervous はソケットサーバの機能も果たしており、上位層のプログラムからのマルチコネクションを受け入れ、セ
ンサ情報・アクチュエータ情報の受け渡し、自律調節機能プラグイン … の起動・終了・パラメータ調節などのコマンドイン
タフェースも提供する … 双方向ソケットを開き、センサ周期と同じ周期でセンサ情報クラスのインスタンスを生成するストリン
グをソケットに送信しつつ、コマンドやアクチュエータ情報を非同期に受信しボディに送信するデータを更新する". C.2.2: one
reader thread per connection, every line through the same ``interpreter()``.

Here one asyncio event loop runs everything: a task per connection reads lines and interprets them in
order, a task writes each connection's queued lines, and the packet task runs one tick per sensor packet
(real time or as fast as possible, :mod:`shintai.nervous.hal`). Lines are interpreted between two ticks, so
a command and the packet loop never see each other half done. What protects the loop from its clients:

* **bounded output** — each connection queues at most ``max_queue`` stream lines; a client reading slower
  than it streams loses state lines (counted in ``dropped``, shown by ``stats``), the loop never waits for
  it. Replies are never dropped: a client that stops reading stops being read (TCP back-pressure), and one
  whose queue passes ``hard_limit`` lines is disconnected.
* **bounded input** — a line longer than :data:`~shintai.nervous.protocol.MAX_LINE_BYTES` is discarded up to
  its newline and answered with one ``error:``; a connection that closes in the middle of a line or of a
  stream is cleaned up and its half line is never executed.
* **loopback by default** — the server binds 127.0.0.1 unless told otherwise; nothing a client sends is
  passed to a shell (the thesis's rule 5 is refused), and a plugin file path is honoured only in the
  start-up file.
"""

from __future__ import annotations

import asyncio
import contextlib
import signal
import socket
import sys
import threading
import time
from collections import deque
from collections.abc import Callable
from pathlib import Path

from shintai.nervous.commands import Client, Reply
from shintai.nervous.nerve import Nerve
from shintai.nervous.protocol import MAX_LINE_BYTES, ProtocolError, decode, error

DEFAULT_HOST = "127.0.0.1"
MAX_QUEUE = 256  # chosen: stream lines queued per client (0.26 s of 1 ms packets)
HARD_LIMIT = 10_000  # chosen: lines of any kind queued for one client before it is dropped as dead
READ_CHUNK = 65536


class Connection(Client):
    """One client's socket: its bounded outbox and the task that writes it."""

    def __init__(self, server: Server, reader: asyncio.StreamReader, writer: asyncio.StreamWriter, number: int):
        peer = writer.get_extra_info("peername")
        super().__init__(f"client{number}@{peer[0]}:{peer[1]}" if peer else f"client{number}")
        self.server, self.reader, self.writer = server, reader, writer
        self.outbox: deque[str] = deque()
        self.streamed = 0  # stream lines in the outbox
        self.wake = asyncio.Event()
        self.closed = False

    def send(self, line: str, droppable: bool = False) -> None:
        if self.closed:
            return
        if droppable:
            if self.streamed >= self.server.max_queue:
                self.dropped += 1
                return
            self.streamed += 1
            line = "\x00" + line  # marks a stream line in the outbox (never in a line: decode refuses NUL)
        if len(self.outbox) >= self.server.hard_limit:
            self.server.nerve.event(f"{self.name} dropped: {len(self.outbox)} lines unread")
            self.close()
            return
        self.outbox.append(line)
        self.wake.set()

    async def write_loop(self) -> None:
        try:
            while not self.closed:
                await self.wake.wait()
                self.wake.clear()
                while self.outbox and not self.closed:
                    lines = []
                    while self.outbox and len(lines) < 512:
                        line = self.outbox.popleft()
                        if line.startswith("\x00"):
                            self.streamed -= 1
                            line = line[1:]
                        lines.append(line)
                    self.writer.write(("\n".join(lines) + "\n").encode())
                    await self.writer.drain()
        except (ConnectionError, OSError):
            self.close()

    def close(self) -> None:
        if not self.closed:
            self.closed = True
            self.wake.set()
            with contextlib.suppress(Exception):
                self.writer.close()


class Console(Client):
    """Standard input's client: what it is sent is printed."""

    closed = False

    def __init__(self, out):
        super().__init__("console")
        self.out = out

    def send(self, line: str, droppable: bool = False) -> None:
        print(line, file=self.out, flush=True)


class Server:
    """nervous's TCP server around a :class:`~shintai.nervous.nerve.Nerve`."""

    def __init__(self, nerve: Nerve, host: str = DEFAULT_HOST, port: int = 0, max_queue: int = MAX_QUEUE,
                 hard_limit: int = HARD_LIMIT, send_buffer: int | None = None):
        self.nerve, self.host, self.port = nerve, host, port
        self.max_queue, self.hard_limit = max_queue, hard_limit
        self.send_buffer = send_buffer  # the kernel's send buffer per client (bytes; None: the system's)
        self.connections: set[Connection] = set()
        self._handlers: set[asyncio.Task] = set()
        self._count = 0
        self._server: asyncio.base_events.Server | None = None
        self._packets: asyncio.Task | None = None
        self._stopping = False

    # -- start-up file ----------------------------------------------------------------------------

    def run_rc(self, path: str | Path, out=sys.stderr) -> int:
        """Interpret a start-up file (C.1.4 ``.nervousrc``) as trusted lines; each error is printed with its
        line number. Returns the number of errors."""
        client = Client("rc")
        errors = 0
        for number, line in enumerate(Path(path).read_text(encoding="utf-8").splitlines(), 1):
            try:
                text = decode(line.encode("utf-8"))
            except ProtocolError as exc:
                print(f"nervous: {path}:{number}: error: {exc}", file=out)
                errors += 1
                continue
            reply = self.nerve.execute(text, client, trusted=True)
            if reply.wait is not None:
                reply.text = error("wait: not in a start-up file (no packets run yet)")
            if reply.text is not None and reply.text.startswith("error:"):
                print(f"nervous: {path}:{number}: {reply.text}", file=out)
                errors += 1
        return errors

    # -- serving ----------------------------------------------------------------------------------

    async def start(self) -> None:
        self._server = await asyncio.start_server(self._handle, self.host, self.port, limit=MAX_LINE_BYTES)
        self.port = self._server.sockets[0].getsockname()[1]
        self._packets = asyncio.create_task(self._packet_loop())

    @property
    def address(self) -> str:
        return f"{self.host}:{self.port}"

    async def serve_forever(self) -> None:
        await self._packets

    async def close(self) -> None:
        self._stopping = True
        if self._server is not None:
            self._server.close()
        for conn in list(self.connections):
            conn.close()
        if self._handlers:
            await asyncio.wait(list(self._handlers), timeout=5)
        if self._packets is not None:
            self._packets.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._packets
        for inst in list(self.nerve.instances.values()):
            if inst.running:
                self.nerve.stop_instance(inst)
        self.nerve.interface.close_interface()

    async def _packet_loop(self) -> None:
        nerve = self.nerve
        while not self._stopping:
            if nerve.halted is not None:
                await asyncio.sleep(0.05)
                continue
            delay = nerve.interface.ready_in()
            await asyncio.sleep(delay)  # 0: let the clients' tasks run between packets
            nerve.tick()

    # -- one connection ---------------------------------------------------------------------------

    async def _handle(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        self._count += 1
        sock = writer.get_extra_info("socket")
        if self.send_buffer is not None and sock is not None:
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, self.send_buffer)
        task = asyncio.current_task()
        self._handlers.add(task)
        conn = Connection(self, reader, writer, self._count)
        self.connections.add(conn)
        self.nerve.clients.add(conn)
        writing = asyncio.create_task(conn.write_loop())
        try:
            await self._read_loop(conn)
        except (ConnectionError, OSError):
            pass
        finally:
            self.nerve.clients.discard(conn)
            self.nerve.dropped_gone += conn.dropped
            self.nerve.motions.forget(conn)
            self.connections.discard(conn)
            if not conn.closed:  # let the last replies go out, then close
                conn.wake.set()
                with contextlib.suppress(asyncio.TimeoutError, Exception):
                    await asyncio.wait_for(self._flushed(conn), 1.0)
                conn.close()
            writing.cancel()
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await writing
            self._handlers.discard(task)

    @staticmethod
    async def _flushed(conn: Connection) -> None:
        while conn.outbox and not conn.closed:
            await asyncio.sleep(0.001)
        with contextlib.suppress(Exception):
            await conn.writer.drain()

    async def _read_loop(self, conn: Connection) -> None:
        buffer = b""
        skipping = 0  # bytes of an over-long line being discarded
        while not conn.closed:
            chunk = await conn.reader.read(READ_CHUNK)
            if not chunk:
                return  # EOF: a half line left in the buffer is never executed
            buffer += chunk
            while True:
                cut = buffer.find(b"\n")
                if cut < 0:
                    if len(buffer) > MAX_LINE_BYTES:
                        skipping += len(buffer)
                        buffer = b""
                    break
                raw, buffer = buffer[:cut], buffer[cut + 1:]
                if skipping:
                    size, skipping = skipping + len(raw), 0
                    conn.send(error(f"line too long ({size} bytes, the limit is {MAX_LINE_BYTES})"))
                    continue
                if not await self._line(conn, raw):
                    return

    async def read_stdin(self, stream=None, out=None) -> None:
        """The operator's console (C.2.1: nervous reads "socket(と標準入力)"): lines from standard input are
        interpreted like a client's, as trusted as the start-up file; replies and events go to ``out``."""
        loop = asyncio.get_running_loop()
        reader = asyncio.StreamReader(limit=MAX_LINE_BYTES + 1)
        await loop.connect_read_pipe(lambda: asyncio.StreamReaderProtocol(reader), stream or sys.stdin)
        console = Console(out or sys.stdout)
        self.nerve.clients.add(console)
        try:
            while True:
                try:
                    raw = await reader.readline()
                except (ValueError, asyncio.LimitOverrunError):
                    console.send(error(f"line too long (the limit is {MAX_LINE_BYTES} bytes)"))
                    continue
                if not raw:
                    return
                if not await self._line(console, raw.rstrip(b"\n"), trusted=True):
                    return
        finally:
            self.nerve.clients.discard(console)

    async def _line(self, conn: Connection, raw: bytes, trusted: bool = False) -> bool:
        """Interpret one line and answer it; False when the client asked to quit."""
        while len(getattr(conn, "outbox", ())) >= self.max_queue + 64 and not conn.closed:  # not reading: stop reading it
            await asyncio.sleep(0.005)
        try:
            text = decode(raw)
        except ProtocolError as exc:
            conn.send(error(str(exc)))
            return True
        reply = self.nerve.execute(text, conn, trusted=trusted)
        if reply.wait is not None:
            await self._wait(conn, reply)
        if reply.text is not None:
            conn.send(reply.text)
        for line in reply.after:
            conn.send(line)
        return not (reply.text == "ok bye")

    async def _wait(self, conn: Connection, reply: Reply) -> None:
        """``wait``: answer when every motion has ended, or with an error at the deadline."""
        done = asyncio.get_running_loop().create_future()
        left = {id(m) for m in reply.wait}

        def ended(motion):
            left.discard(id(motion))
            if not left and not done.done():
                done.set_result(None)

        for m in reply.wait:
            m.when_finished(ended)
        if not reply.wait:
            done.set_result(None)
        timeout = max(0.0, reply.deadline - time.monotonic()) if reply.deadline is not None else None
        try:
            await asyncio.wait_for(asyncio.shield(done), timeout)
            summary = " ".join(f"{m.id or '-'}:{m.status}" for m in reply.wait)
            reply.text = "ok " + (summary or "nothing pending")
        except asyncio.TimeoutError:
            late = [m.id or "-" for m in reply.wait if not m.finished]
            reply.text = error(f"wait {reply.wait_for}: {' '.join(late)} not done after "
                               f"{1e3 * (timeout or 0):.0f} ms")


class ServerThread:
    """A server on its own thread and event loop (for scenarios, tests and benchmarks that are its
    clients in the same process). ``call(fn)`` runs ``fn()`` on the server's thread between two packets
    (a scenario's world: the hand that holds Cla's spine, the seat that tilts)."""

    def __init__(self, nerve: Nerve, host: str = DEFAULT_HOST, port: int = 0, **options):
        self.server = Server(nerve, host, port, **options)
        self.loop = asyncio.new_event_loop()
        self._ready = threading.Event()
        self._error: BaseException | None = None
        self.thread = threading.Thread(target=self._run, name="nervous", daemon=True)

    def _run(self) -> None:
        asyncio.set_event_loop(self.loop)
        try:
            self.loop.run_until_complete(self.server.start())
        except BaseException as exc:  # noqa: BLE001 - handed to the starting thread
            self._error = exc
            self._ready.set()
            return
        self._ready.set()
        self.loop.run_forever()

    def __enter__(self) -> ServerThread:
        self.thread.start()
        if not self._ready.wait(30):
            raise TimeoutError("nervous server did not start within 30 s")
        if self._error is not None:
            raise self._error
        return self

    def __exit__(self, *exc) -> None:
        self.stop()

    @property
    def host(self) -> str:
        return self.server.host

    @property
    def nerve(self) -> Nerve:
        return self.server.nerve

    @property
    def port(self) -> int:
        return self.server.port

    def call(self, fn: Callable, timeout: float = 30.0):
        """Run ``fn()`` on the server's thread (between packets); its result."""
        async def run():
            return fn()
        return asyncio.run_coroutine_threadsafe(run(), self.loop).result(timeout)

    def stop(self) -> None:
        if self.loop.is_closed():
            return
        if self.thread.is_alive():
            try:
                asyncio.run_coroutine_threadsafe(self.server.close(), self.loop).result(30)
            finally:
                self.loop.call_soon_threadsafe(self.loop.stop)
                self.thread.join(30)
        self.loop.close()


async def serve(nerve: Nerve, host: str = DEFAULT_HOST, port: int = 0, rc: str | None = None,
                announce: Callable[[str], None] = print, stdin: bool = False, **options) -> None:
    """``shintai nervous serve``: the start-up file, then listen until SIGINT or SIGTERM; ``announce`` gets
    ``nervous: listening on HOST:PORT`` once connections are accepted. Stopping runs every running
    plugin's destructor (a log file is closed) and closes the interface."""
    server = Server(nerve, host, port, **options)
    if rc is not None:
        server.run_rc(rc)
    await server.start()
    loop = asyncio.get_running_loop()
    stop = asyncio.Event()
    handled = []
    for sig in (signal.SIGINT, signal.SIGTERM):
        with contextlib.suppress(NotImplementedError, RuntimeError, ValueError):
            loop.add_signal_handler(sig, stop.set)
            handled.append(sig)
    announce(f"nervous: listening on {server.address}")
    console = asyncio.create_task(server.read_stdin()) if stdin else None
    stopping = asyncio.create_task(stop.wait())
    try:
        await asyncio.wait({server._packets, stopping}, return_when=asyncio.FIRST_COMPLETED)
    finally:
        stopping.cancel()
        if console is not None:
            console.cancel()
        for sig in handled:
            loop.remove_signal_handler(sig)
        await server.close()
