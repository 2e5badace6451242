# The RTL sources of cube4_top, dependencies first, one path per line relative to rtl/.
# The one list: read by the Makefile (lint), the simulation runner, the testbenches and
# synthesis. For synthesis, a file with a counterpart of the same name in rtl/ecp5/
# (the vendor layer) is replaced by that counterpart. Include directory: rtl/.
cube4_round_shift.v
cube4_prim_copies.v
cube4_prim_reg_copies.v
cube4_prim_spread.v
cube4_prim_reg_en.v
cube4_lerp.v
cube4_skid.v
cube4_credit_fifo.v
cube4_ring_shift.v
cube4_mul.v
cube4_prim_ebr.v
cube4_sdp_ram.v
cube4_dual_read_ram.v
cube4_voxel_mem.v
cube4_beam_ext.v
cube4_cfb.v
cube4_clip.v
cube4_tri_src.v
cube4_tri_beam.v
cube4_tri_meta.v
cube4_tri_lane.v
cube4_tri.v
cube4_frontend.v
cube4_delay_line.v
cube4_gra_lines.v
cube4_gra_walk.v
cube4_gra_window.v
cube4_gra_arith.v
cube4_gra.v
cube4_sha.v
cube4_com_seq.v
cube4_com_walk.v
cube4_com_rect.v
cube4_com_plw.v
cube4_com_bpb.v
cube4_com_blend.v
cube4_com_ext.v
cube4_com_lane.v
cube4_com.v
cube4_stream_hold.v
cube4_stream_check.v
cube4_frame_ctl.v
cube4_top.v
