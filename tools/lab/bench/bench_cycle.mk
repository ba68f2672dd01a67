# tools/lab/bench/bench_cycle.mk - hl-bench-cycle: the online cycle (hl_slam_update) timed and
# fingerprinted over a recorded tour's SONAR scans (docs/results/performance.md).
#
#   make BUILD=... $(BUILD)/bin/hl-bench-cycle && $(BUILD)/bin/hl-bench-cycle --reps 5

LAB_BINS += $(BUILD)/bin/hl-bench-cycle

$(BUILD)/bin/hl-bench-cycle: $(call obj,tools/lab/bench/bench_cycle.c) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	$(Q)$(CC) -o $@ $(filter %.o,$^) $(BUS_LIB) $(BUS_LDLIBS)
