// cube4_unit_params.vh: the parameters every unit harness of GRA and COM shares (tb/cube4_gra_*,
// tb/cube4_com_*), included in the harness's parameter list right after "#(": the build
// parameters of the unit (ranges as in its header) and the geometry and view layout derived
// from them (rtl/cube4_defs.vh). No include guard: every harness of a lint run includes it.
// It ends with a comma: the harness's own parameters follow.
    parameter integer P           = 5,
    parameter integer MAX_DIM     = 32,
    parameter integer MAX_SS_LOG2 = 0,
    parameter integer WEIGHT_W    = 8,
    `CUBE4_GEOMETRY,
    `CUBE4_VIEW_LAYOUT,
