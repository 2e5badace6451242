# One precompiled verilated.h for every one-file simulation build (cube4_sim.runner adds
# this makefile after Vtop.mk: make -f Vtop.mk -f shared_pch.mk CUBE4_PCH_ROOT=<dir>).
#
# Verilator writes a small model (a unit's harness) as one file, Vtop__ALL.cpp, and about
# half of that file's C++ time is parsing verilated.h (1.5 of 3.3 s for COM's extremum
# lane). This compiles verilated.h once per compiler and set of flags into a precompiled
# header under CUBE4_PCH_ROOT/<12 hex digits of the flags' SHA-1>/ and has the one-file
# compile include it first.
#
# Models split into several files (cube4_top, the front end) use the same shared header
# instead of Verilator's per-build one (Vtop__pch.h: verilated.h with the model's own
# headers, compiled twice per build, for the fast and the slow files: 14 s of CPU for a
# P = 5 cube4_top, more than its model files at -O1). Each file then reads the model's
# headers as text (about half a second each); the slow files get a shared header of their
# own flags (-O0). The per-build header targets remain as empty stamps, so that
# verilated.mk's rules, which name them as prerequisites, still hold.
#
# The header is built with exactly the flags of the compile that uses it (the same make
# variables, in the same order), under a lock, into a temporary file renamed into place,
# so builds running at once share one. If g++ still finds it unusable it reads the
# header as text (no -Winvalid-pch): slower, never different.

ifneq ($(CUBE4_PCH_ROOT),)
# the flags of a compile at optimisation level $(1) (as verilated.mk orders them), and the
# shared header for them: CUBE4_PCH_ROOT/<12 hex digits of their SHA-1>/cube4_verilated.h
cube4_pch_flags = $(filter-out -MMD -MP,$(1) $(CXXFLAGS) $(CPPFLAGS))
cube4_pch_h = $(CUBE4_PCH_ROOT)/$(shell printf '%s' '$(CXX) $(call cube4_pch_flags,$(1))' | sha1sum | cut -c1-12)/cube4_verilated.h

# the rule that compiles header $(1) with the flags of level $(2), once, under a lock
define cube4_pch_rule
$(1).gch:
	@mkdir -p $(dir $(1))
	flock $(dir $(1)).lock sh -c 'test -f $$@ || { printf "#include \"verilated.h\"\n" > $(1) && $(CXX) $(call cube4_pch_flags,$(2)) -x c++-header $(1) -o $$@.$$$$$$$$ && mv $$@.$$$$$$$$ $$@; }'
endef

CUBE4_PCH_H := $(call cube4_pch_h,$(OPT_FAST))
CUBE4_PCH_H_SLOW := $(call cube4_pch_h,$(OPT_SLOW))
$(eval $(call cube4_pch_rule,$(CUBE4_PCH_H),$(OPT_FAST)))
$(if $(filter-out $(CUBE4_PCH_H),$(CUBE4_PCH_H_SLOW)),$(eval $(call cube4_pch_rule,$(CUBE4_PCH_H_SLOW),$(OPT_SLOW))))

# one-file models: their one compile includes the fast header first
$(VM_PREFIX)__ALL.o: $(CUBE4_PCH_H).gch
$(VM_PREFIX)__ALL.o: CPPFLAGS += -include $(CUBE4_PCH_H)

# models in several files: the fast and slow files include the shared headers, and the
# per-build headers verilated.mk's rules name as prerequisites are empty stamps
VK_PCH_I_FAST = -include $(CUBE4_PCH_H)
VK_PCH_I_SLOW = -include $(CUBE4_PCH_H_SLOW)

$(VK_PCH_H).fast.gch: $(CUBE4_PCH_H).gch
	@touch $@
$(VK_PCH_H).slow.gch: $(CUBE4_PCH_H_SLOW).gch
	@touch $@
endif
