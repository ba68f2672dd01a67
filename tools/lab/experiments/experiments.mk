# tools/lab/experiments/experiments.mk - the paper's experiments, rerun (hl-experiments;
# docs/results/experiments.md).
#
#   make experiments        run all three in paper and improved modes; results, tables
#                           and figures in build/experiments/
#   make experiments-seeds  the same over 10 layouts (seeds) of the lab and the corridor
#                           world: build/experiments/seeds.tsv
#                           (tools/lab/experiments/seeds_tsv.sh)

EXP_SRCS := tools/lab/experiments/experiments.cpp tools/lab/experiments/dataset.cpp \
            tools/lab/experiments/modes.cpp tools/lab/experiments/table1.cpp \
            tools/lab/experiments/orientation.cpp tools/lab/experiments/combined.cpp \
            tools/lab/experiments/figures.cpp tools/lab/experiments/report.cpp \
            tools/lab/experiments/overrides.cpp tools/lab/experiments/limits.cpp

LAB_BINS += $(BUILD)/bin/hl-experiments

# render.mk is read after this file, so its library is named by path.
$(BUILD)/bin/hl-experiments: $(call obj,$(EXP_SRCS)) $(BUILD)/lib/libhoughloc_render.a $(SIM_LIB) $(ROBOT_LIB) \
                             $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CXX) -o $@ $^ $(CAIRO_LIBS) $(PKG_LIBS) $(SYS_LIBS)

.PHONY: experiments experiments-seeds
experiments-seeds: deps
	$(Q)$(MAKE) --no-print-directory $(BUILD)/bin/hl-experiments $(BUILD)/bin/hl-sim-logs
	$(Q)BUILD=$(BUILD) sh tools/lab/experiments/seeds_tsv.sh $(SEEDS)

SEEDS ?= 10

experiments: deps
	$(Q)$(MAKE) --no-print-directory $(BUILD)/bin/hl-experiments
	$(Q)$(BUILD)/bin/hl-experiments --logs logs --out $(BUILD)/experiments
