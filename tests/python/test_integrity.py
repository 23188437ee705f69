"""`binary info`, `post` and `export` on truncated or corrupted results files: a clear
message and exit 1, never a crash and never numbers that are wrong."""
import os
import random
import shutil
import subprocess

import pytest

from conftest import run


@pytest.mark.parametrize("fraction", [0.999, 0.5, 0.05])
def test_truncated_file(binary, crash1, tmp_path, fraction):
    cut = tmp_path / "cut.h5"
    shutil.copy(crash1, cut)
    os.truncate(cut, int(os.path.getsize(crash1) * fraction))
    for args in (["info", str(cut)], ["post", str(cut), "--nsol", "7,UX"],
                 ["export", str(cut), "-o", str(tmp_path)]):
        p = run([binary, *args], expect=1)
        assert p.stderr.startswith("error: "), p.stderr
        assert "truncated" in p.stderr or "damaged" in p.stderr or "not an impactfe" in p.stderr


def test_random_corruption(binary, crash1, tmp_path):
    reference = {
        "info": run([binary, "info", crash1]).stdout.replace(crash1, "F"),
        "post": run([binary, "post", crash1, "--nsol", "7,UX", "--esol", "6,SAXL", "--gapf",
                     "1"]).stdout,
    }
    rng = random.Random(7)
    size = os.path.getsize(crash1)
    reported = 0
    for trial in range(25):
        bad = tmp_path / "bad.h5"
        shutil.copy(crash1, bad)
        at = rng.randrange(0, size - 16)
        with open(bad, "r+b") as f:
            f.seek(at)
            f.write(bytes(rng.randrange(256) for _ in range(16)))
        for name, args in (("info", ["info", str(bad)]),
                           ("post", ["post", str(bad), "--nsol", "7,UX", "--esol", "6,SAXL",
                                     "--gapf", "1"])):
            p = subprocess.run([binary, *args], capture_output=True, text=True)
            assert p.returncode in (0, 1), f"{name} exited {p.returncode} (bytes at {at})"
            if p.returncode == 0:
                out = p.stdout.replace(str(bad), "F")
                assert out == reference[name], f"{name} returned changed output (bytes at {at})"
            else:
                assert p.stderr.startswith("error: ") and "results file" in p.stderr, p.stderr
                reported += 1
    assert reported > 0
