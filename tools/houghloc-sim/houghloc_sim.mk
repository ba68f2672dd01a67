# tools/houghloc-sim/houghloc_sim.mk - houghloc-sim, the simulated ARCOS robot on TCP
# (C++17, built on the simulator library of tools/sim and the ARCOS codec of src/robot),
# and its unit tests in tests/houghloc-sim/. Included by the top Makefile.
#
# This file is read before tools/sim/sim.mk (the includes are sorted), so SIM_LIB and
# SIM_ASAN_LIB are still empty here: the prerequisites below name those libraries by
# path; recipes, expanded later, may use the variables.

HLSIMR_SRCS := tools/houghloc-sim/motion.cpp tools/houghloc-sim/simrobot.cpp \
               tools/houghloc-sim/connection.cpp tools/houghloc-sim/server.cpp \
               tools/houghloc-sim/options.cpp tools/houghloc-sim/teleport.cpp
HLSIMR_OBJS      := $(call obj,$(HLSIMR_SRCS) tools/houghloc-sim/main.cpp)
HLSIMR_ASAN_OBJS := $(patsubst %.cpp,$(BUILD)/asan/%.o,$(HLSIMR_SRCS))
HLSIMR_CPPFLAGS  := -Itools/houghloc-sim -Itools/sim
HLSIMR_SIM_LIB      := $(BUILD)/lib/libhoughloc_sim.a
HLSIMR_SIM_ASAN_LIB := $(BUILD)/lib/libhoughloc_sim_asan.a

HLSIMR_TEST_SRCS := $(wildcard tests/houghloc-sim/test_*.cpp)
HLSIMR_TESTS     := $(patsubst tests/houghloc-sim/%.cpp,$(BUILD)/tests/houghloc-sim/%,$(HLSIMR_TEST_SRCS))

BINS      += $(BUILD)/bin/houghloc-sim
TEST_BINS += $(HLSIMR_TESTS)

# Static pattern rules: only this fragment's files get the simulator's include path.
$(HLSIMR_OBJS): $(BUILD)/obj/%.o: %.cpp | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CXX     $<"
	$(Q)$(CXX) $(CPPFLAGS) $(HLSIMR_CPPFLAGS) $(PKG_CFLAGS) $(CXXFLAGS) -c -o $@ $<

# The tests include tests/sim/test_support.hpp (cmocka from C++).
$(HLSIMR_ASAN_OBJS) $(patsubst %.cpp,$(BUILD)/asan/%.o,$(HLSIMR_TEST_SRCS)): $(BUILD)/asan/%.o: %.cpp | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CXX-SAN $<"
	$(Q)$(CXX) $(CPPFLAGS) $(HLSIMR_CPPFLAGS) -Itests/sim $(PKG_CFLAGS) $(CXXFLAGS) $(SAN) -c -o $@ $<

$(BUILD)/bin/houghloc-sim: $(HLSIMR_OBJS) $(HLSIMR_SIM_LIB) $(ROBOT_LIB) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CXX) -o $@ $(HLSIMR_OBJS) $(SIM_LIB) $(ROBOT_LIB) $(BUS_LIB) $(BUS_LDLIBS)

# The tests link the sanitized model, connection, server and options with the sanitized
# simulator, codec, bus (channel names) and core.
$(BUILD)/tests/houghloc-sim/%: $(BUILD)/asan/tests/houghloc-sim/%.o $(HLSIMR_ASAN_OBJS) \
                               $(HLSIMR_SIM_ASAN_LIB) $(ROBOT_ASAN_LIB) $(BUS_ASAN_LIB) \
                               $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CXX) $(SAN) -o $@ $^ $(CMOCKA_LIBS) $(PKG_LIBS) $(SODIUM_LIBS) $(SYS_LIBS)
