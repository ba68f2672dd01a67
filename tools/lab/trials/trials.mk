# tools/lab/trials/trials.mk - `make trials`: every reliability trial in one run, under 15
# minutes here, progress on stderr, one machine-readable last line
# (tools/lab/trials/trials.sh; docs/results/reliability.md). FUZZ_SECONDS (30) per fuzz
# target; TRIALS_SKIP="flood sanitizers" leaves trials out. Included by tools/lab/lab.mk,
# after tests/fuzz/fuzz.mk (read with the product's fragments), whose regression replays
# it builds with hl-flood and hl-forge (flood.mk); `make fuzz` itself is run by the
# script, in the background.
.PHONY: trials
TRIALS_PROGS := $(addprefix $(BUILD)/bin/,houghlocd houghloc-sim houghloc-goto houghloc-ctl \
                  hl-eval houghloc-import-carmen hl-flood hl-forge hl-poison)
trials: deps
	$(Q)$(MAKE) --no-print-directory $(TRIALS_PROGS) $(FUZZ_REPLAYS)
	$(Q)MAKE="$(MAKE)" BUILD=$(BUILD) FUZZ_SECONDS=$(or $(FUZZ_SECONDS),30) sh tools/lab/trials/trials.sh

# hl-console-load: the Console trial's load on houghloc-console (tools/lab/trials/console.sh):
# large MAPs, event streams that stop reading, slowloris connections (console_load.c).
CONSOLE_LOAD_OBJS := $(BUILD)/obj/tools/lab/trials/console_load.o \
                     $(BUILD)/obj/tools/lab/trials/trial_args.o
LAB_BINS += $(BUILD)/bin/hl-console-load
$(BUILD)/bin/hl-console-load: $(CONSOLE_LOAD_OBJS) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(CONSOLE_LOAD_OBJS) $(BUS_LIB) $(BUS_LDLIBS)
TRIALS_PROGS += $(BUILD)/bin/houghloc-console $(BUILD)/bin/hl-console-load

# hl-counter-edge: the Counters trial's tool (tools/lab/trials/counters.sh): sets a real map
# file's version near a 32-bit edge, and reads the MAP and STATUS versions of an output log.
COUNTER_EDGE_OBJS := $(BUILD)/obj/tools/lab/trials/counter_edge.o
LAB_BINS += $(BUILD)/bin/hl-counter-edge
$(BUILD)/bin/hl-counter-edge: $(COUNTER_EDGE_OBJS) $(STORE_LIB) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(COUNTER_EDGE_OBJS) $(STORE_LIB) $(STORE_LDLIBS)
TRIALS_PROGS += $(BUILD)/bin/hl-counter-edge
