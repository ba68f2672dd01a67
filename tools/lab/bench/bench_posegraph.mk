# tools/lab/bench/bench_posegraph.mk - hl-bench-posegraph: loop closure's fit timed on a
# synthetic graph of any size (docs/results/performance.md; `make bench` runs 256 and 4096 stops).

LAB_BINS += $(BUILD)/bin/hl-bench-posegraph

$(BUILD)/bin/hl-bench-posegraph: $(call obj,tools/lab/bench/bench_posegraph.c) $(BENCH_CORRIDOR_OBJ) $(TEST_SUPPORT_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	$(Q)$(CC) -o $@ $^ $(SYS_LIBS)
