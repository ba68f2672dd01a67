# src/solve/solve.mk - the solve layer: sparse symmetric positive definite systems of 3 x 3
# blocks on Eigen's sparse Cholesky, behind the C interface of houghloc-internal/solve.h
# (include/internal/core)
# (C++17; Eigen's include path is this layer's alone, never the core's). Its objects go
# into the core's library (SOLVE_SRCS, Makefile), whose pose-graph fit calls it; a
# program linking the core adds $(SYS_LIBS) (the C++ runtime).

SOLVE_TESTS := $(patsubst tests/solve/%.c,$(BUILD)/tests/solve/%,$(wildcard tests/solve/test_*.c))
TEST_BINS += $(SOLVE_TESTS)

$(BUILD)/obj/src/solve/%.o: src/solve/%.cpp
	@mkdir -p $(@D)
	@echo "  CXX     $<"
	$(Q)$(CXX) $(CORE_CPPFLAGS) $(CXXFLAGS) $(HIDDEN) -c -o $@ $<
$(BUILD)/asan/src/solve/%.o: src/solve/%.cpp
	@mkdir -p $(@D)
	@echo "  CXX-SAN $<"
	$(Q)$(CXX) $(CORE_CPPFLAGS) $(CXXFLAGS) $(HIDDEN) $(SAN) -c -o $@ $<

$(BUILD)/tests/solve/%: $(BUILD)/asan/tests/solve/%.o $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -o $@ $^ $(CMOCKA_LIBS) $(SYS_LIBS)
# The solve layer's tests read its interface, an internal header.
$(BUILD)/asan/tests/solve/%.o: CPPFLAGS += $(CORE_INTERNAL_INC)
