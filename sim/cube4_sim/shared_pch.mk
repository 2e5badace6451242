# One precompiled verilated.h for every one-file simulation build (cube4_sim.runner adds
# this makefile after Vtop.mk: make -f Vtop.mk -f shared_pch.mk CUBE4_PCH_ROOT=<dir>).
#
# Verilator writes a small model (a unit's harness) as one file, Vtop__ALL.cpp, and about
# half of that file's C++ time is parsing verilated.h (1.5 of 3.3 s for COM's extremum
# lane). This compiles verilated.h once per compiler and set of flags into a precompiled
# header under CUBE4_PCH_ROOT/<12 hex digits of the flags' SHA-1>/ and has the one-file
# compile include it first. Models split into several files (cube4_top, the front end)
# have no Vtop__ALL.o target and keep Verilator's own per-build precompiled header.
#
# The header is built with exactly the flags of the compile that uses it (the same make
# variables, in the same order), under a lock, into a temporary file renamed into place,
# so builds running at once share one. If g++ still finds it unusable it reads the
# header as text (no -Winvalid-pch): slower, never different.

ifneq ($(CUBE4_PCH_ROOT),)
CUBE4_PCH_FLAGS := $(filter-out -MMD -MP,$(OPT_FAST) $(CXXFLAGS) $(CPPFLAGS))
CUBE4_PCH_DIR := $(CUBE4_PCH_ROOT)/$(shell printf '%s' '$(CXX) $(CUBE4_PCH_FLAGS)' | sha1sum | cut -c1-12)
CUBE4_PCH_H := $(CUBE4_PCH_DIR)/cube4_verilated.h

$(CUBE4_PCH_H).gch:
	@mkdir -p $(CUBE4_PCH_DIR)
	flock $(CUBE4_PCH_DIR)/.lock sh -c 'test -f $@ || { printf "#include \"verilated.h\"\n" > $(CUBE4_PCH_H) && $(CXX) $(CUBE4_PCH_FLAGS) -x c++-header $(CUBE4_PCH_H) -o $@.$$$$ && mv $@.$$$$ $@; }'

$(VM_PREFIX)__ALL.o: $(CUBE4_PCH_H).gch
$(VM_PREFIX)__ALL.o: CPPFLAGS += -include $(CUBE4_PCH_H)
endif
