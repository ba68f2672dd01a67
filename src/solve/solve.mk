# src/solve/solve.mk - the solve layer: sparse symmetric positive definite systems of 3 x 3
# blocks on Eigen's sparse Cholesky, behind the C interface of include/houghloc/solve.h
# (C++17; Eigen's include path is this layer's alone, never the core's). A program
# linking $(SOLVE_LIB) links with $(CXX) (or adds -lstdc++).

SOLVE_SRCS      := $(sort $(wildcard src/solve/*.cpp))
SOLVE_OBJS      := $(call obj,$(SOLVE_SRCS))
SOLVE_ASAN_OBJS := $(patsubst %.cpp,$(BUILD)/asan/%.o,$(SOLVE_SRCS))
SOLVE_LIB       := $(BUILD)/lib/libhoughloc_solve.a
SOLVE_ASAN_LIB  := $(BUILD)/lib/libhoughloc_solve_asan.a

SOLVE_TESTS := $(patsubst tests/solve/%.c,$(BUILD)/tests/solve/%,$(wildcard tests/solve/test_*.c))
TEST_BINS += $(SOLVE_TESTS)

$(SOLVE_LIB): $(SOLVE_OBJS)
$(SOLVE_ASAN_LIB): $(SOLVE_ASAN_OBJS)

$(BUILD)/asan/src/solve/%.o: src/solve/%.cpp
	@mkdir -p $(@D)
	@echo "  CXX-SAN $<"
	$(Q)$(CXX) $(CORE_CPPFLAGS) $(CXXFLAGS) $(SAN) -c -o $@ $<

# The tests are C (cmocka); the library is C++, so they link with $(CXX).
$(BUILD)/tests/solve/%: $(BUILD)/asan/tests/solve/%.o $(SOLVE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CXX) $(SAN) -o $@ $^ $(CMOCKA_LIBS) -lm
