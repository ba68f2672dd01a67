# tools/trials/trials.mk - `make trials` (issue 13): every reliability trial in one run,
# under 15 minutes here, progress on stderr, one machine-readable last line
# (tools/trials/trials.sh; docs/reliability-trials.md). FUZZ_SECONDS (30) per fuzz target;
# TRIALS_SKIP="flood sanitizers" leaves trials out. Included by the top Makefile, after
# tests/fuzz/fuzz.mk and tools/trials/flood.mk (the includes are sorted), whose programs
# and regression replays it builds when they exist; `make fuzz` itself is run by the
# script, in the background.
.PHONY: trials
TRIALS_PROGS := $(addprefix $(BUILD)/bin/,houghlocd houghloc-sim houghloc-goto houghloc-ctl \
                  hl-eval houghloc-import-carmen) \
                $(filter $(BUILD)/bin/hl-flood $(BUILD)/bin/hl-forge,$(BINS))
trials: deps
	$(Q)$(MAKE) --no-print-directory $(TRIALS_PROGS) $(FUZZ_REPLAYS)
	$(Q)MAKE="$(MAKE)" BUILD=$(BUILD) FUZZ_SECONDS=$(or $(FUZZ_SECONDS),30) sh tools/trials/trials.sh
