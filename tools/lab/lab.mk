# tools/lab/lab.mk - the laboratory: the programs and scripts that measure houghloc (the
# paper's experiments, relocalization, the real buildings, reliability trials, benchmarks,
# the simulated data sets). Nothing here is installed; `make` does not build it.
# Included by the top Makefile after every product fragment, so the product's libraries
# ($(SIM_LIB), $(DAEMON_LIB), ...) are defined here.
#
#   make lab                 every lab program (LAB_BINS)
#   make bench               tools/lab/bench          (docs/results/performance.md)
#   make logs                tools/lab/sim-logs       the simulated data sets in logs/
#   make experiments         tools/lab/experiments    (docs/results/experiments.md)
#   make experiments-seeds
#   make kidnap              tools/lab/kidnap         (docs/results/relocalization.md)
#   make eval-real           tools/lab/realeval       (docs/results/real-buildings.md)
#   make trials              tools/lab/trials         (docs/results/reliability.md)
#   make lab-test            the laboratory's own tests (tools/lab/tests): its unit tests
#                            (LAB_TEST_BINS) under the sanitizers, then its integration
#                            scripts (LAB_INTEGRATION_TESTS); make test runs none of them
# (make fuzz and make crash-trials are the tests' own: tests/fuzz/fuzz.mk, src/daemon.)
#
# Each folder's fragment adds its programs to LAB_BINS and its tests to LAB_TEST_BINS and
# LAB_INTEGRATION_TESTS. The benchmarks link the tests' support library
# (tests/support/support.mk, read with the product's fragments).

# The research tools may read the core's private modules (the pose graph, loop closure's
# matcher) through houghloc-internal/, the internal headers; the product's tools may not.
# Of the daemon's, only the tools that read its configuration (kidnap.mk) add theirs.
$(BUILD)/obj/tools/lab/%.o $(BUILD)/asan/tools/lab/%.o: CPPFLAGS += $(CORE_INTERNAL_INC)
# The simulator's headers and the experiments' dataset reader by their include paths
# (tools/sim/sim.mk compiles the simulator the same way), never by relative paths.
$(BUILD)/obj/tools/lab/experiments/%.o $(BUILD)/asan/tools/lab/experiments/%.o \
$(BUILD)/obj/tools/lab/kidnap/%.o $(BUILD)/asan/tools/lab/kidnap/%.o: \
    CPPFLAGS += -Itools/sim -Itools/lab/experiments

# The programs, the data sets and the experiments end to end (test_tools.sh).
LAB_TEST_BINS :=
LAB_INTEGRATION_TESTS := tools/lab/tests/test_tools.sh

include $(sort $(wildcard tools/lab/*/*.mk))

.PHONY: lab lab-test lab-unit-test
lab: $(LAB_BINS)

lab-test: deps
	$(Q)$(MAKE) --no-print-directory all lab
	$(Q)$(MAKE) --no-print-directory lab-unit-test
	$(Q)sh tests/run-integration.sh $(LAB_INTEGRATION_TESTS)

lab-unit-test: $(LAB_TEST_BINS)
	$(Q)sh tests/run-unit.sh $(LAB_TEST_BINS)
