"""The sweeps' progress bar (tqdm), the same for every executor: its unit is the tasks'
estimated seconds (Task.weight), so the time left is the rate so far applied to what is left."""
import sys
import threading

from tqdm import tqdm


class Bar:
    def __init__(self, total: float, desc: str):
        # smoothing=0: the average rate so far; a ticker redraws every 2 s so a long step (a
        # Yosys run) still shows time passing.
        self.bar = tqdm(total=total, unit="s~", desc=desc, dynamic_ncols=True, smoothing=0,
                        bar_format="{desc}: {percentage:3.0f}%|{bar}| {elapsed} elapsed, ~{remaining} left {postfix}")
        self.stop = threading.Event()
        self.lock = threading.Lock()
        if sys.stderr.isatty():  # in a log file, one line a step is enough
            threading.Thread(target=self._tick, daemon=True).start()

    def _tick(self):
        while not self.stop.wait(2):
            with self.lock:
                self.bar.refresh()

    def status(self, text: str):
        with self.lock:
            self.bar.set_postfix_str(text)

    def advance(self, weight: float):
        with self.lock:
            self.bar.update(weight)

    def write(self, line: str):
        with self.lock:
            self.bar.write(line, file=sys.stderr)

    def close(self):
        self.stop.set()
        with self.lock:
            self.bar.close()
