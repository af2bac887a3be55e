"""Runs `softsub` as a separate process (never inside Blender's), reads its `--stats`
lines for progress, stops it with SIGTERM, and turns its exit into a message. Pure
Python, no bpy: the Blender operators and the tests drive the same class."""
import os
import queue
import signal
import subprocess
import threading

EXIT_MEANING = {1: "internal error", 2: "bad input", 3: "I/O error", 4: "the simulation blew up",
                130: "stopped"}


def run_command(exe, scene_path, out_dir=None, formats=None, extra=()):
    cmd = [exe, "run", scene_path, "--stats"]
    if out_dir:
        cmd += ["--out", out_dir]
    if formats:
        cmd += ["--formats", formats]
    return cmd + list(extra)


class Runner:
    """One softsub process. poll() returns the frames finished so far; done() is None
    while it runs, else its exit code; message() says what went wrong."""

    def __init__(self, cmd, total_frames):
        self.cmd = list(cmd)
        self.total = total_frames
        self.frame = -1
        self.stderr_lines = []
        self.cancelled = False
        self._lines = queue.Queue()
        try:
            self.proc = subprocess.Popen(self.cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                         stdin=subprocess.DEVNULL, text=True, bufsize=1)
        except OSError as e:
            raise RunnerError(f"cannot start '{self.cmd[0]}': {e.strerror} (set the softsub executable "
                              "in the add-on's preferences)") from None
        self._threads = [threading.Thread(target=self._read, args=(self.proc.stdout, "out"), daemon=True),
                         threading.Thread(target=self._read, args=(self.proc.stderr, "err"), daemon=True)]
        for t in self._threads:
            t.start()

    def _read(self, stream, which):
        for line in stream:
            self._lines.put((which, line.rstrip("\n")))
        stream.close()

    def poll(self):
        """Consumes pending output; returns the last frame finished (-1 before frame 0)."""
        while True:
            try:
                which, line = self._lines.get_nowait()
            except queue.Empty:
                break
            if which == "err":
                self.stderr_lines.append(line)
            elif line and not line.startswith("#"):
                try:
                    self.frame = int(line.split()[0])
                except ValueError:
                    pass
        return self.frame

    def done(self):
        return self.proc.poll()

    def wait(self, timeout=None):
        code = self.proc.wait(timeout)
        for t in self._threads:
            t.join()
        self.poll()
        return code

    def cancel(self):
        """SIGTERM: softsub finishes the frame in progress, writes it and exits 130."""
        self.cancelled = True
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)

    def progress(self):
        """0..1 from the frames finished (frame 0 is the initial state)."""
        if self.total <= 0:
            return 1.0 if self.frame >= 0 else 0.0
        return max(0.0, min(1.0, self.frame / self.total))

    def warnings(self):
        """The simulator's warnings (each about this run's result: an unstable setting,
        a fast object, a default function at another scale), each once, in order."""
        out = []
        for line in self.stderr_lines:
            if line.startswith("warning:") and line not in out:
                out.append(line)
        return out

    def message(self):
        """The simulator's own error line (or a summary of the exit, with its warnings),
        for the user."""
        code = self.proc.returncode
        errors = [l for l in self.stderr_lines if l.startswith("error:")]
        warned = self.warnings()
        said = f"; {len(warned)} warning{'s' if len(warned) > 1 else ''}: " + " ".join(warned) if warned else ""
        if code == 0:
            return f"softsub: done, frames 0..{self.frame}{said}"
        if code == 130:
            return f"softsub: stopped; frames 0..{self.frame} are complete{said}"
        if errors:
            return "softsub: " + " ".join(errors)
        tail = " ".join(self.stderr_lines[-3:]) or "no message"
        meaning = EXIT_MEANING.get(code, f"killed by signal {-code}" if code and code < 0 else "failed")
        return f"softsub: {meaning} (exit code {code}): {tail}"


class RunnerError(Exception):
    pass


def run_tool(cmd, timeout=None):
    """Runs a short softsub command (fill, info): (exit code, stdout, stderr)."""
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, stdin=subprocess.DEVNULL)
    except OSError as e:
        raise RunnerError(f"cannot start '{cmd[0]}': {e.strerror} (set the softsub executable "
                          "in the add-on's preferences)") from None
    return p.returncode, p.stdout, p.stderr


def error_line(stderr, code):
    lines = [l for l in stderr.splitlines() if l.startswith("error:")]
    return " ".join(lines) if lines else f"exit code {code}: {stderr.strip()[-300:] or 'no message'}"
