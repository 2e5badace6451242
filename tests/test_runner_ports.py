"""The runner's reading of a top module's interface (names made public to cocotb)."""

from __future__ import annotations

from pathlib import Path

from cube4_sim.runner import top_interface


def test_several_ports_and_parameters_per_line(tmp_path: Path):
    src = tmp_path / "m.v"
    src.write_text(
        "module m #(\n"
        "    parameter integer P = 8, parameter integer ALPHA_W = 12,\n"
        "    localparam integer W = P * 2\n"
        ") (\n"
        "    input  wire clk, input wire rst,   // clock, reset\n"
        "    input  wire in_valid, output wire in_ready, input wire [W-1:0] in_hdr,\n"
        "    output wire [P*(24+ALPHA_W)-1:0] out_rgba,\n"
        "    output reg  [3:0] q\n"
        ");\n"
        "endmodule\n")
    assert top_interface([src], "m") == ["P", "ALPHA_W", "W", "clk", "rst", "in_valid", "in_ready",
                                          "in_hdr", "out_rgba", "q"]


def test_every_port_of_cube4_top():
    rtl = Path(__file__).resolve().parents[1] / "rtl"
    names = top_interface([rtl / "cube4_top.v"], "cube4_top")
    for port in ("clk", "ld_data", "cfg_ni", "cfg_i_lin", "cfg_sy", "cfg_cut_d", "pix_rgba", "pix_eop", "dbg_hold"):
        assert port in names
    assert "ALPHA_W" in names and "ADDR_W" in names


def test_ports_declared_by_a_header_macro(tmp_path: Path):
    """A port list line that is a header macro (CUBE4_VIEW_PORTS) counts the ports its
    body declares; a macro of parameters adds nothing."""
    (tmp_path / "defs.vh").write_text(
        "`define PORTS \\\n"
        "    input  wire [3:0] cfg_a, \\\n"
        "    input  wire       cfg_b,\n"
        "`define PARAMS \\\n"
        "    localparam integer X = 2\n")
    src = tmp_path / "m.v"
    src.write_text(
        "`include \"defs.vh\"\n"
        "module m #(\n"
        "    parameter integer P = 8, `PARAMS\n"
        ") (\n"
        "    `PORTS\n"
        "    input  wire clk\n"
        ");\n"
        "endmodule\n")
    assert top_interface([src], "m") == ["P", "cfg_a", "cfg_b", "clk"]


def test_parameters_declared_by_a_nested_header_macro(tmp_path: Path):
    """A macro of parameters (CUBE4_BUILD_PARAMS, which uses CUBE4_GEOMETRY) counts its
    parameters, nested ones too, but not its localparams; parameters after it on its line
    count as well."""
    (tmp_path / "defs.vh").write_text(
        "`define LAYOUT \\\n"
        "    localparam integer X = 2\n"
        "`define BUILD \\\n"
        "    parameter integer P = 8, parameter integer Q = 1, \\\n"
        "    `LAYOUT\n")
    src = tmp_path / "m.v"
    src.write_text(
        "`include \"defs.vh\"\n"
        "module m #(\n"
        "    `BUILD, parameter integer R = 3\n"
        ") (\n"
        "    input  wire clk\n"
        ");\n"
        "endmodule\n")
    assert top_interface([src], "m") == ["P", "Q", "R", "clk"]
