# tools/lab/bench/bench_solve.mk - hl-bench-solve: one Gauss-Newton step's solve of loop
# closure's normal equations on the solve layer's sparse Cholesky (src/solve) against
# Eigen's conjugate gradients (docs/results/pose-graph-solver.md).

LAB_BINS += $(BUILD)/bin/hl-bench-solve

$(BUILD)/bin/hl-bench-solve: $(call obj,tools/lab/bench/bench_solve.cpp) $(BENCH_CORRIDOR_OBJ) $(TEST_SUPPORT_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	$(Q)$(CXX) -o $@ $^ $(SYS_LIBS)
