# tools/lab/bench/bench.mk - hl-bench, the localization benchmark on synthetic scenes, and
# `make bench`: every benchmark at -O2 (docs/results/performance.md).
#
#   make bench    hl-bench (one line per workload), hl-bench-posegraph and hl-bench-solve
#                 on 256 and 4096 stops, then houghlocd replaying logs/tour.lcmlog
#                 (bench_daemon.sh); the localizer's and the daemon's lines become
#                 docs/results/bench-table.md (bench_table.sh), the page README.md and
#                 performance.md link for their figures
BENCH_OUT   := $(BUILD)/bench
BENCH_TABLE := docs/results/bench-table.md

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
	@mkdir -p $(BENCH_OUT)
	$(Q)$(BUILD)/bin/hl-bench | tee $(BENCH_OUT)/localizer.txt
	$(Q)$(BUILD)/bin/hl-bench-posegraph --stops 256
	$(Q)$(BUILD)/bin/hl-bench-posegraph --stops 4096
	$(Q)$(BUILD)/bin/hl-bench-solve --stops 256
	$(Q)$(BUILD)/bin/hl-bench-solve --stops 4096
	$(Q)BUILD=$(BUILD) sh tools/lab/bench/bench_daemon.sh | tee $(BENCH_OUT)/daemon.txt
	$(Q)sh tools/lab/bench/bench_table.sh $(BENCH_OUT)/localizer.txt $(BENCH_OUT)/daemon.txt \
	    >$(BENCH_OUT)/table.md && mv $(BENCH_OUT)/table.md $(BENCH_TABLE) && \
	    echo "bench: $(BENCH_TABLE) written"
