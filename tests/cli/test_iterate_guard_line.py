"""``throwmap iterate`` refused by its work guard writes one line on stderr, as every command does.

With more throws planned than the progress bar's threshold, the bar was opened before the guard refused the work,
and its closing newline made the error two lines (an empty one first)."""

import subprocess
import sys


def test_iterate_over_its_limits_is_refused_in_one_line():
    p = subprocess.run([sys.executable, "-m", "throwmap", "iterate", "--part", "triangle", "--h", "-0.01", "--x", "0.2",
                        "--side", "0", "--omega", "4", "-n", "100000000000"], capture_output=True, text=True, timeout=300)
    assert p.returncode == 2
    lines = p.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: n: iterate on 100,000,000,000 throws needs"), p.stderr
