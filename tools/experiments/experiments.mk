# tools/experiments/experiments.mk - the paper's experiments, rerun (hl-experiments).
#
#   make experiments        run all three in paper and improved modes; results, tables
#                           and figures in build/experiments/
#   make experiments-seeds  the same over 10 layouts (seeds) of the lab and the corridor
#                           world: build/experiments/seeds.tsv (tools/experiments/seeds_tsv.sh)

EXP_SRCS := tools/experiments/experiments.cpp tools/experiments/dataset.cpp \
            tools/experiments/modes.cpp tools/experiments/table1.cpp \
            tools/experiments/orientation.cpp tools/experiments/combined.cpp \
            tools/experiments/figures.cpp tools/experiments/report.cpp \
            tools/experiments/overrides.cpp tools/experiments/limits.cpp

BINS += $(BUILD)/bin/hl-experiments

# render.mk and sim.mk are read after this file, so name their libraries by path.
$(BUILD)/bin/hl-experiments: $(call obj,$(EXP_SRCS)) $(BUILD)/lib/libhoughloc_render.a $(BUILD)/lib/libhoughloc_sim.a $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CXX) -o $@ $^ $(CAIRO_LIBS) $(PKG_LIBS) -lm

.PHONY: experiments experiments-seeds
experiments-seeds: deps
	$(Q)$(MAKE) --no-print-directory $(BUILD)/bin/hl-experiments $(BUILD)/bin/hl-sim-logs
	$(Q)BUILD=$(BUILD) sh tools/experiments/seeds_tsv.sh $(SEEDS)

SEEDS ?= 10

experiments: deps
	$(Q)$(MAKE) --no-print-directory $(BUILD)/bin/hl-experiments
	$(Q)$(BUILD)/bin/hl-experiments --logs logs --out $(BUILD)/experiments
