"""python -m cube4_reports.unit_fpga: its arguments (the synthesis itself takes a minute
and runs by hand, docs/architecture.md "The front end's plan")."""

from __future__ import annotations

import pytest

from cube4.errors import UserError
from cube4_reports import unit_fpga


def test_params_and_unit_names():
    assert unit_fpga.parse_params(["P=8", "MAX_DIM=128"]) == {"P": 8, "MAX_DIM": 128}
    for bad in (["P8"], ["p=8"], ["P=x"]):
        with pytest.raises(UserError, match="NAME=integer"):
            unit_fpga.parse_params(bad)
    with pytest.raises(UserError, match="cube4_"):
        unit_fpga.run("../etc", {}, 140.0, 1)


def test_bad_arguments_are_one_line(capsys):
    assert unit_fpga.main(["cube4_cfb_skip", "--param", "P=eight"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "NAME=integer" in err[0]
