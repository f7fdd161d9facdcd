"""Named checks for the CLI test scripts: one line per check ("ok - NAME" or "FAIL: NAME: DETAIL"),
then "N passed, M failed" and the exit status."""
import sys


class Checks:
    """Call with (ok, name, detail) for each check; finish() prints the count and exits."""

    def __init__(self):
        self.passed = self.failed = 0

    def __call__(self, ok, name, detail=""):
        print(("ok - " if ok else "FAIL: ") + name + (": " + detail if detail else ""))
        if ok:
            self.passed += 1
        else:
            self.failed += 1

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        sys.exit(1 if self.failed else 0)
