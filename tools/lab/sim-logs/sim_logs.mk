# tools/lab/sim-logs/sim_logs.mk - the lab's programs on the simulator library
# (tools/sim): hl-sim-logs makes the simulated data sets, hl-calibrate fits a sonar's
# calibration from range pairs, hl-sim-draw draws a world and its tour.
#
#   make logs    rebuild logs/lab28.lcmlog, logs/orientation.lcmlog, logs/tour.lcmlog (the
#                paper's experiments), logs/continuous.lcmlog and logs/laser.lcmlog (the
#                inputs of the continuous sensor profiles' goldens, tests/golden)
#                (deterministic: byte-identical every time)

LAB_BINS += $(BUILD)/bin/hl-sim-logs $(BUILD)/bin/hl-calibrate $(BUILD)/bin/hl-sim-draw

.PHONY: logs
logs: $(BUILD)/bin/hl-sim-logs
	@mkdir -p logs
	$(Q)$(BUILD)/bin/hl-sim-logs --seed 1 --continuous --out-dir logs

# The simulator's headers by its include path, as tools/sim/sim.mk compiles them.
$(call obj,$(wildcard tools/lab/sim-logs/*.cpp)): CPPFLAGS += -Itools/sim

$(BUILD)/bin/hl-sim-logs: $(call obj,tools/lab/sim-logs/make_logs.cpp) $(SIM_LIB) $(ROBOT_LIB) $(BUS_LIB) \
                          $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CXX) -o $@ $^ $(PKG_LIBS) $(SYS_LIBS)

$(BUILD)/bin/hl-calibrate: $(call obj,tools/lab/sim-logs/calibrate.cpp) $(SIM_LIB) $(ROBOT_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CXX) -o $@ $^ $(SYS_LIBS)

$(BUILD)/bin/hl-sim-draw: $(call obj,tools/lab/sim-logs/draw_world.cpp) $(SIM_LIB) $(ROBOT_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CXX) -o $@ $^ $(CAIRO_LIBS) $(SYS_LIBS)
