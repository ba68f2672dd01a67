# tools/kidnap/kidnap.mk - make kidnap: the global relocalization (hl_slam_relocalize,
# include/houghloc/reloc.h) of a robot set down anywhere in a known map, heading unknown.
# Included by the top Makefile.
#
#   make -j2 kidnap                          every row, two at a time
#   make kidnap KIDNAP_TRIALS_SIM=50 KIDNAP_TRIALS_REAL=20 BUILDINGS='intel aces'
#   make kidnap BUILDINGS= KIDNAP_WORLDS=lab  the simulated lab only
#   make kidnap DATA=/elsewhere              the data folder (holding raw/), as eval-real
#   make kidnap BUILDINGS= KIDNAP_TOUR_SEED=3 the simulated rows on another tour
#
# Writes $(BUILD)/experiments/kidnap.tsv, one row per (world, input):
#   world input trials success_pct ambiguous_pct wrong_pct median_ms p90_ms
# - the simulated worlds (lab, corridor), sonar: the map is the one houghlocd makes on its
#   tour of the world (hl-sim-logs --seed KIDNAP_TOUR_SEED, 1 by default, replayed in
#   batch with the compiled-in defaults from the true start pose, so that the map's frame
#   is the world's); the tests
#   are KIDNAP_TRIALS_SIM soundings of the same robot at random free poses, random
#   headings (tools/kidnap/sim.cpp), relocalized with the compiled-in defaults but for
#   what tools/kidnap/WORLD.conf sets (corridor.conf: a larger coarse raster);
# - the real buildings, laser and pseudo-sonar: KIDNAP_TRIALS_REAL test scans spread
#   evenly over the import (tools/realeval's, every scan), each relocalized in a map of
#   every scan more than 2 m from it at its true pose (tools/kidnap/real.cpp), with the
#   parameters of tools/realeval/INPUT.conf.
# Each row runs again at every `make kidnap` (the core is being tuned); the tours, maps
# and imports are files, made again only when their inputs change. Rows, per-trial detail
# and progress logs are in $(KIDNAP_OUT). Progress on stderr; the table and a summary line
# last on stdout.

KIDNAP_OUT         ?= $(BUILD)/kidnap
KIDNAP_TSV         ?= $(BUILD)/experiments/kidnap.tsv
KIDNAP_TRIALS_SIM  ?= 200
KIDNAP_TRIALS_REAL ?= 100
KIDNAP_WORLDS      ?= lab corridor
# The tour that makes the simulated worlds' maps. The lab's row turns on it: seed 1's tour
# is the best of 12 tried (docs/kidnap.md, "The lab row is one tour's").
KIDNAP_TOUR_SEED   ?= 1
# The map-making tour runs without the daemon's own lost mode (daemon.lost_after,
# daemon.search_every), which calls the very search under test: the map must not depend
# on it. It keeps its map by evidence (slam.cull_choices, map.h): the paper's uniform cull
# leaves a 1,500-vector map of the lab half spurious echoes and half forgotten (49 % found
# against 86 % on the same drift-free tour, docs/kidnap.md).
KIDNAP_TOUR_SET    ?= daemon.lost_after=0 daemon.search_every=0 slam.cull_choices=16
# As tools/realeval/realeval.mk (read after this file) sets them: the same defaults.
DATA      ?= ../shared/data
BUILDINGS ?= intel aces freiburg-079 csail freiburg-101
EVAL_OUT  ?= $(BUILD)/eval

KIDNAP_SRCS := tools/kidnap/kidnap.cpp tools/kidnap/trials.cpp tools/kidnap/sim.cpp \
               tools/kidnap/real.cpp
KIDNAP_OBJS := $(call obj,$(KIDNAP_SRCS)) \
               $(call obj,tools/experiments/dataset.cpp tools/experiments/modes.cpp)
KIDNAP_ROWS := $(foreach w,$(KIDNAP_WORLDS),$(KIDNAP_OUT)/rows/$(w)_sonar.tsv) \
               $(foreach b,$(BUILDINGS),$(foreach i,laser sonar,$(KIDNAP_OUT)/rows/$(b)_$(i).tsv))
KIDNAP_ENV = BUILD='$(BUILD)' DATA='$(DATA)' EVAL_OUT='$(EVAL_OUT)' KIDNAP_OUT='$(KIDNAP_OUT)' \
             KIDNAP_TRIALS_SIM='$(KIDNAP_TRIALS_SIM)' KIDNAP_TRIALS_REAL='$(KIDNAP_TRIALS_REAL)' \
             KIDNAP_TOUR_SET='$(KIDNAP_TOUR_SET)' KIDNAP_TOUR_SEED='$(KIDNAP_TOUR_SEED)'

BINS += $(BUILD)/bin/hl-kidnap
INTEGRATION_TESTS += tests/integration/test_kidnap.sh

# hl-kidnap reads the daemon's configuration and map files with the daemon's own code
# (src/daemon: config.h, mapstore.h), the logs with the experiments' reader.
$(call obj,$(KIDNAP_SRCS)): $(BUILD)/obj/%.o: %.cpp | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CXX     $<"
	$(Q)$(CXX) $(CPPFLAGS) -Isrc/daemon $(PKG_CFLAGS) $(CXXFLAGS) -c -o $@ $<

# sim.mk is read after this file, so its library is named by path.
$(BUILD)/bin/hl-kidnap: $(KIDNAP_OBJS) $(BUILD)/lib/libhoughloc_sim.a $(DAEMON_LIB) $(ROBOT_LIB) \
                        $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CXX) -o $@ $(KIDNAP_OBJS) $(BUILD)/lib/libhoughloc_sim.a $(DAEMON_LIB) $(DAEMON_LDLIBS)

.PHONY: kidnap kidnap-rows kidnap-always

# deps first (as eval-real); then every row that can run (-k: a building without data
# fails alone, with its line), then the table, which needs them all.
kidnap: deps
	$(Q)t0=$$(date +%s); rm -f $(KIDNAP_OUT)/rows/*.tsv; \
	$(MAKE) --no-print-directory -k kidnap-rows; st=$$?; \
	BUILD='$(BUILD)' sh tools/kidnap/table.sh '$(KIDNAP_TSV)' $$(( $$(date +%s) - t0 )) \
	    $(KIDNAP_ROWS) && exit $$st

kidnap-rows: $(KIDNAP_ROWS)

# The tour's seed as a file that changes only with it, so that another seed makes the
# tours (and everything after them) again.
KIDNAP_SEED_FILE := $(KIDNAP_OUT)/sim/tour-seed
$(KIDNAP_SEED_FILE): kidnap-always
	$(Q)mkdir -p $(@D); echo '$(KIDNAP_TOUR_SEED)' | cmp -s - $@ || echo '$(KIDNAP_TOUR_SEED)' >$@

# kidnap_sim WORLD: its tour, the daemon's map of it, the row.
define kidnap_sim
$(KIDNAP_OUT)/sim/$(1)/tour.lcmlog: $(BUILD)/bin/hl-sim-logs tools/kidnap/run_row.sh $(KIDNAP_SEED_FILE) \
        $(if $(filter lab,$(1)),tools/sim/worlds/lab.world,tools/sim/worlds/$(1).world)
	$$(Q)$$(KIDNAP_ENV) sh tools/kidnap/run_row.sh tour $(1)
$(KIDNAP_OUT)/sim/$(1)/map.hlmap: $(KIDNAP_OUT)/sim/$(1)/tour.lcmlog $(BUILD)/bin/houghlocd \
        $(BUILD)/bin/hl-eval
	$$(Q)$$(KIDNAP_ENV) sh tools/kidnap/run_row.sh map $(1)
$(KIDNAP_OUT)/rows/$(1)_sonar.tsv: kidnap-always $(KIDNAP_OUT)/sim/$(1)/map.hlmap \
        $(BUILD)/bin/hl-kidnap $(wildcard tools/kidnap/$(1).conf)
	$$(Q)$$(KIDNAP_ENV) sh tools/kidnap/run_row.sh sim $(1)
endef

# kidnap_real BUILDING INPUT: the import by realeval.mk's rule when the data is there;
# without it the row says so in one line.
define kidnap_real
$(KIDNAP_OUT)/rows/$(1)_$(2).tsv: kidnap-always $(BUILD)/bin/hl-kidnap tools/realeval/$(2).conf \
        $(wildcard tools/kidnap/$(2)-search.conf) \
        $(if $(wildcard $(DATA)/raw/$(1)-raw.log.gz),$(if $(wildcard $(DATA)/raw/$(1)-groundtruth.tum),\
             $(EVAL_OUT)/input/$(1)_$(2)_every.lcmlog))
	$$(Q)$$(KIDNAP_ENV) sh tools/kidnap/run_row.sh real $(1) $(2)
endef

$(foreach w,$(KIDNAP_WORLDS),$(eval $(call kidnap_sim,$(w))))
$(foreach b,$(BUILDINGS),$(foreach i,laser sonar,$(eval $(call kidnap_real,$(b),$(i)))))
