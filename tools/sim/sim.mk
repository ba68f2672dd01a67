# tools/sim/sim.mk - the sonar world simulator library (worlds, sonar, laser, robot, tours,
# log writer), on which houghloc-sim is built, and its tests. Included by the top Makefile.
# The lab's programs on it (hl-sim-logs, hl-calibrate, hl-sim-draw, `make logs`) are in
# tools/lab/sim-logs/sim_logs.mk.

SIM_SRCS := tools/sim/world.cpp tools/sim/sonar.cpp tools/sim/robot.cpp \
            tools/sim/calib_fit.cpp tools/sim/tour.cpp tools/sim/logwriter.cpp \
            tools/sim/layout.cpp tools/sim/laser.cpp
SIM_WORLD_SRC := $(BUILD)/gen/sim_lab_world.cpp

SIM_LIB      := $(BUILD)/lib/libhoughloc_sim.a
SIM_ASAN_LIB := $(BUILD)/lib/libhoughloc_sim_asan.a
SIM_OBJS      := $(call obj,$(SIM_SRCS)) $(BUILD)/obj/gen/sim_lab_world.o
SIM_ASAN_OBJS := $(patsubst %.cpp,$(BUILD)/asan/%.o,$(SIM_SRCS)) $(BUILD)/asan/gen/sim_lab_world.o
# What a program linking $(SIM_LIB) also needs, after it on the command line (the log
# writer encodes through the bus codecs, src/bus/bus.mk).
SIM_LDLIBS := $(ROBOT_LIB) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB) $(PKG_LIBS) $(SYS_LIBS)

SIM_TESTS := $(patsubst tests/sim/%.cpp,$(BUILD)/tests/sim/%,$(wildcard tests/sim/test_*.cpp))

TEST_BINS += $(SIM_TESTS)

# The default world is compiled in, so the tools work from any directory: each line
# of the world file becomes one string literal.
$(SIM_WORLD_SRC): tools/sim/worlds/lab.world tools/sim/sim.mk
	@mkdir -p $(@D)
	$(Q){ echo '// Generated from tools/sim/worlds/lab.world by tools/sim/sim.mk.'; \
	  echo '#include "world.hpp"'; \
	  echo 'const char *hlsim::World::lab_text()'; \
	  echo '{'; \
	  echo '    return'; \
	  sed -e 's/\\/\\\\/g' -e 's/"/\\"/g' -e 's/^/        "/' -e 's/$$/\\n"/' $<; \
	  echo '        "";'; \
	  echo '}'; } > $@.tmp && mv $@.tmp $@

$(BUILD)/obj/gen/sim_lab_world.o: $(SIM_WORLD_SRC)
	@mkdir -p $(@D)
	$(Q)$(CXX) $(CPPFLAGS) -Itools/sim $(CXXFLAGS) -c -o $@ $<
$(BUILD)/asan/gen/sim_lab_world.o: $(SIM_WORLD_SRC)
	@mkdir -p $(@D)
	$(Q)$(CXX) $(CPPFLAGS) -Itools/sim $(CXXFLAGS) $(SAN) -c -o $@ $<

# Sanitized C++ objects for the tests (the top Makefile's sanitized rule is C only).
$(BUILD)/asan/tools/sim/%.o: tools/sim/%.cpp | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CXX-SAN $<"
	$(Q)$(CXX) $(CPPFLAGS) $(PKG_CFLAGS) $(CXXFLAGS) $(SAN) -c -o $@ $<
$(BUILD)/asan/tests/sim/%.o: tests/sim/%.cpp | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CXX-SAN $<"
	$(Q)$(CXX) $(CPPFLAGS) -Itools/sim $(PKG_CFLAGS) $(CXXFLAGS) $(SAN) -c -o $@ $<

$(SIM_LIB): $(SIM_OBJS)
$(SIM_ASAN_LIB): $(SIM_ASAN_OBJS)

$(BUILD)/tests/sim/%: $(BUILD)/asan/tests/sim/%.o $(SIM_ASAN_LIB) $(ROBOT_ASAN_LIB) $(LCM_LIB) $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CXX) $(SAN) -o $@ $^ $(CMOCKA_LIBS) $(PKG_LIBS) $(SYS_LIBS)
