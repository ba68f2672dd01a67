# tools/lab/bench/bench.mk - hl-bench, the localization benchmark on synthetic scenes, and
# `make bench`: every benchmark at -O2 (docs/results/performance.md).
#
#   make bench    hl-bench (one line per workload), hl-bench-posegraph and hl-bench-solve
#                 on 256 and 4096 stops, then houghlocd replaying logs/tour.lcmlog (bench_daemon.sh)

LAB_BINS += $(BUILD)/bin/hl-bench

# The benchmarks' scenes: the tests' synthetic rooms and reference localizer
# (tests/support), and the loop-closure graph of hl-bench-posegraph and hl-bench-solve
# (corridor.c, on the rooms' random numbers).
$(BUILD)/obj/tools/lab/bench/%.o: CPPFLAGS += $(TEST_SUPPORT_INC)
BENCH_CORRIDOR_OBJ := $(call obj,tools/lab/bench/corridor.c)

$(BUILD)/bin/hl-bench: $(call obj,tools/lab/bench/bench_localize.c) $(TEST_SUPPORT_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	$(Q)$(CC) -o $@ $^ $(SYS_LIBS)

.PHONY: bench
bench: deps
	$(Q)$(MAKE) --no-print-directory $(BUILD)/bin/hl-bench $(BUILD)/bin/houghlocd $(BUILD)/bin/hl-eval \
	    $(BUILD)/bin/hl-bench-posegraph $(BUILD)/bin/hl-bench-solve OPT="-O2 -g"
	$(Q)$(BUILD)/bin/hl-bench
	$(Q)$(BUILD)/bin/hl-bench-posegraph --stops 256
	$(Q)$(BUILD)/bin/hl-bench-posegraph --stops 4096
	$(Q)$(BUILD)/bin/hl-bench-solve --stops 256
	$(Q)$(BUILD)/bin/hl-bench-solve --stops 4096
	$(Q)BUILD=$(BUILD) sh tools/lab/bench/bench_daemon.sh
