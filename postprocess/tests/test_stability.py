"""The stability-map table from a manifest of real runs: converged runs get
their Newton statistics and wear difference, failed runs their error."""

from __future__ import annotations

import csv
import os
import subprocess
from pathlib import Path

import pytest

from corrugation_post.stability import evaluate, markdown

BIN = os.environ.get("CORRUGATION_BIN")
REPO = Path(__file__).resolve().parents[2]


@pytest.mark.skipif(not BIN, reason="CORRUGATION_BIN not set (scripts/test.sh sets it)")
def test_stability_table_reports_outcomes(tmp_path):
    rows = []
    for label, sets in (("baseline", []), ("eps", ["contact.regularisation=1e-4"]),
                        ("bad", ["contact.regularisation=-1"])):
        f = tmp_path / f"{label}.h5"
        cmd = [BIN, "run", str(REPO / "configs" / "paper_normal_15mm.toml"), "-o", str(f),
               "--set", "contact.model=simplified-transient", "--set", "contact.elements_x=6",
               "--set", "contact.elements_y=6"]
        for s in sets:
            cmd += ["--set", s]
        done = subprocess.run(cmd, capture_output=True, text=True)
        rows.append({"sweep": label, "value": "0", "file": str(f), "exit_code": str(done.returncode),
                     "message": done.stderr.splitlines()[0] if done.returncode else ""})
    out = evaluate(rows)
    assert out[0]["outcome"] == "converged" and out[0]["wear_l2_vs_baseline"] == 0.0
    assert out[1]["outcome"] == "converged" and 0.0 < out[1]["wear_l2_vs_baseline"] < 1.0
    assert out[1]["newton_max"] >= out[1]["newton_mean"] > 0
    assert out[2]["outcome"] == "error (exit 2)" and "invalid config" in out[2]["message"]
    assert "| bad | 0 | error (exit 2)" in markdown(out)
