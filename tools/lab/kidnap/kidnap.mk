# tools/lab/kidnap/kidnap.mk - make kidnap: the global relocalization (hl_slam_relocalize,
# houghloc-internal/slam_search.h; include/core/houghloc/reloc.h) of a robot set down
# anywhere in a known map, heading unknown
# (docs/results/relocalization.md). Included by tools/lab/lab.mk.
#
#   make -j2 kidnap                          every row, two at a time
#   make kidnap KIDNAP_TRIALS_SIM=50 KIDNAP_TRIALS_REAL=20 BUILDINGS='intel aces'
#   make kidnap BUILDINGS= KIDNAP_WORLDS=lab  the simulated lab only
#   make kidnap DATA=/elsewhere              the data folder (holding raw/), as eval-real
#   make kidnap BUILDINGS= KIDNAP_TOUR_SEEDS=3 the simulated rows on one other tour
#
# Writes $(BUILD)/experiments/kidnap.tsv, one row per (world, input):
#   world input trials success_pct ambiguous_pct wrong_pct median_ms p90_ms
# - the simulated worlds (lab, corridor), sonar: the maps are those houghlocd makes on its
#   tours of the world (hl-sim-logs --seed S for each S of KIDNAP_TOUR_SEEDS, replayed in
#   batch with the compiled-in defaults and KIDNAP_TOUR_SET from the true start pose, so
#   that a map's frame is the world's); the tests are KIDNAP_TRIALS_SIM soundings of the
#   same robot at random free poses, random headings, each followed by the robot's next
#   soundings after drives of 0.5-1 m (reloc.scans in all; tools/lab/kidnap/sim.cpp), the
#   same in every map, relocalized with the compiled-in defaults but for what
#   tools/lab/kidnap/WORLD.conf sets (corridor.conf: a larger coarse raster); the row counts
#   every map's trials, and each answer is also judged in its map's own frame
#   (tools/lab/kidnap/map_frame.sh: $(KIDNAP_OUT)/trials/WORLD_sonar.map_frame and stderr);
# - the real buildings, laser and pseudo-sonar: KIDNAP_TRIALS_REAL test scans spread
#   evenly over the import (tools/lab/realeval's, every scan), each with the log's next
#   scans at least 0.5 m apart (reloc.scans in all), relocalized in a map of every scan
#   more than 2 m from all of them at its true pose (tools/lab/kidnap/real.cpp), with the
#   parameters of tools/lab/realeval/INPUT.conf.
# Each row runs again at every `make kidnap` (the core may have changed); the tours, maps
# and imports are files, made again only when their inputs change. Rows, per-trial detail
# and progress logs are in $(KIDNAP_OUT). Progress on stderr; the table and a summary line
# last on stdout.

KIDNAP_OUT         ?= $(BUILD)/kidnap
KIDNAP_TSV         ?= $(BUILD)/experiments/kidnap.tsv
KIDNAP_TRIALS_SIM  ?= 200
KIDNAP_TRIALS_REAL ?= 100
KIDNAP_WORLDS      ?= lab corridor
# The tours that make the simulated worlds' maps. One map's row measures that one tour
# (the same soundings find 12-92 % over different lab tours), so a row averages eight.
KIDNAP_TOUR_SEEDS  ?= 1 2 3 4 5 6 7 8
# What the map-making tour sets, each for the map under test to be the best the daemon
# makes (measurements: docs/results/relocalization.md):
#   slam.lost_after=0 slam.search_every=0       no lost mode: it calls the very search
#                                                under test, and the map must not depend on it
#   slam.cull_choices=16                         keep the map by evidence (map.h), not the
#                                                paper's uniform cull, which forgets walls
#   slam.map_per_place=3 slam.map_square_mm=100  at most 3 vectors of a 100 mm square seen
#                                                from one side: a wall seen at every stop
#                                                must not crowd out the rest
#   slam.map_round_places=false                  ... the squares the lab's rows were
#                                                measured with (round places are measured on
#                                                the real buildings' tracking, not here)
#   slam.refine_heading=false                    refinement fits position only; the heading
#                                                is the Hough peak's
#   slam.close_loops=true                        each stop back near an earlier one is
#                                                matched with it and every stop refitted
#   slam.square_walls=true                       both worlds' walls run along x and y: each
#                                                stop's readings tie its heading to the world
#   slam.long_drive_mm=2000                      after a drive of 2 m or more, also try the
#                                                drive turned by +-6 and +-12 degrees
KIDNAP_TOUR_SET    ?= slam.lost_after=0 slam.search_every=0 slam.cull_choices=16 \
                      slam.map_per_place=3 slam.map_square_mm=100 slam.map_round_places=false \
                      slam.refine_heading=false \
                      slam.close_loops=true slam.square_walls=true slam.long_drive_mm=2000
# As tools/lab/realeval/realeval.mk (read after this file) sets them: the same defaults.
DATA      ?= ../shared/data
BUILDINGS ?= intel aces freiburg-079 csail freiburg-101
EVAL_OUT  ?= $(BUILD)/eval

KIDNAP_SRCS := tools/lab/kidnap/kidnap.cpp tools/lab/kidnap/trials.cpp tools/lab/kidnap/sim.cpp \
               tools/lab/kidnap/real.cpp tools/lab/kidnap/inputs.cpp
KIDNAP_OBJS := $(call obj,$(KIDNAP_SRCS)) \
               $(call obj,tools/lab/experiments/dataset.cpp tools/lab/experiments/modes.cpp)
KIDNAP_ROWS := $(foreach w,$(KIDNAP_WORLDS),$(KIDNAP_OUT)/rows/$(w)_sonar.tsv) \
               $(foreach b,$(BUILDINGS),$(foreach i,laser sonar,$(KIDNAP_OUT)/rows/$(b)_$(i).tsv))
KIDNAP_ENV = BUILD='$(BUILD)' DATA='$(DATA)' EVAL_OUT='$(EVAL_OUT)' KIDNAP_OUT='$(KIDNAP_OUT)' \
             KIDNAP_TRIALS_SIM='$(KIDNAP_TRIALS_SIM)' KIDNAP_TRIALS_REAL='$(KIDNAP_TRIALS_REAL)' \
             KIDNAP_TOUR_SET='$(KIDNAP_TOUR_SET)' KIDNAP_TOUR_SEEDS='$(KIDNAP_TOUR_SEEDS)'

# hl-tour-study: where a tour's error comes from (the tour replayed as houghlocd does,
# with exact motion, or each scan alone against a drift-free map).
TOUR_STUDY_OBJS := $(call obj,tools/lab/kidnap/tour_study.cpp tools/lab/kidnap/inputs.cpp \
                              tools/lab/experiments/dataset.cpp)

LAB_BINS += $(BUILD)/bin/hl-kidnap $(BUILD)/bin/hl-tour-study
LAB_INTEGRATION_TESTS += tools/lab/tests/test_kidnap.sh

# hl-kidnap reads houghlocd's configuration keys through the core's table
# (houghloc-internal/params.h) and map files with the store's code (houghloc/mapstore.h),
# the logs with the experiments' reader; so does hl-tour-study.
$(call obj,$(KIDNAP_SRCS) tools/lab/kidnap/tour_study.cpp): $(BUILD)/obj/%.o: %.cpp | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CXX     $<"
	$(Q)$(CXX) $(CPPFLAGS) $(PKG_CFLAGS) $(CXXFLAGS) -c -o $@ $<

$(BUILD)/bin/hl-kidnap: $(KIDNAP_OBJS) $(SIM_LIB) $(DAEMON_LIB) $(ROBOT_LIB) $(STORE_LIB) \
                        $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CXX) -o $@ $(KIDNAP_OBJS) $(SIM_LIB) $(DAEMON_LIB) $(DAEMON_LDLIBS)

$(BUILD)/bin/hl-tour-study: $(TOUR_STUDY_OBJS) $(DAEMON_LIB) $(ROBOT_LIB) $(STORE_LIB) \
                            $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CXX) -o $@ $(TOUR_STUDY_OBJS) $(DAEMON_LIB) $(DAEMON_LDLIBS)

.PHONY: kidnap kidnap-rows kidnap-always

# deps first (as eval-real); then every row that can run (-k: a building without data
# fails alone, with its line), then the table, which needs them all.
kidnap: deps
	$(Q)t0=$$(date +%s); rm -f $(KIDNAP_OUT)/rows/*.tsv; \
	$(MAKE) --no-print-directory -k kidnap-rows; st=$$?; \
	BUILD='$(BUILD)' sh tools/lab/kidnap/table.sh '$(KIDNAP_TSV)' $$(( $$(date +%s) - t0 )) \
	    $(KIDNAP_ROWS) && exit $$st

kidnap-rows: $(KIDNAP_ROWS)

# The tours' settings as a file that changes only with them, so that other settings make
# the maps (and the rows after them) again.
KIDNAP_SET_FILE := $(KIDNAP_OUT)/sim/tour-set
$(KIDNAP_SET_FILE): kidnap-always
	$(Q)mkdir -p $(@D); echo '$(KIDNAP_TOUR_SET)' | cmp -s - $@ || echo '$(KIDNAP_TOUR_SET)' >$@

# kidnap_tour WORLD SEED: one tour and the daemon's map of it.
define kidnap_tour
$(KIDNAP_OUT)/sim/$(1)/$(2)/tour.lcmlog: $(BUILD)/bin/hl-sim-logs tools/lab/kidnap/run_row.sh \
        tools/sim/worlds/$(1).world
	$$(Q)$$(KIDNAP_ENV) sh tools/lab/kidnap/run_row.sh tour $(1) $(2)
$(KIDNAP_OUT)/sim/$(1)/$(2)/map.hlmap: $(KIDNAP_OUT)/sim/$(1)/$(2)/tour.lcmlog \
        $(BUILD)/bin/houghlocd $(BUILD)/bin/hl-eval $(BUILD)/bin/houghloc-eval $(KIDNAP_SET_FILE)
	$$(Q)$$(KIDNAP_ENV) sh tools/lab/kidnap/run_row.sh map $(1) $(2)
endef

# kidnap_sim WORLD: the row, over every tour's map.
define kidnap_sim
$(KIDNAP_OUT)/rows/$(1)_sonar.tsv: kidnap-always $(BUILD)/bin/hl-kidnap tools/lab/kidnap/map_frame.sh \
        $(foreach s,$(KIDNAP_TOUR_SEEDS),$(KIDNAP_OUT)/sim/$(1)/$(s)/map.hlmap) \
        $(wildcard tools/lab/kidnap/$(1).conf)
	$$(Q)$$(KIDNAP_ENV) sh tools/lab/kidnap/run_row.sh sim $(1)
endef

# kidnap_real BUILDING INPUT: the import by realeval.mk's rule when the data is there;
# without it the row says so in one line.
define kidnap_real
$(KIDNAP_OUT)/rows/$(1)_$(2).tsv: kidnap-always $(BUILD)/bin/hl-kidnap tools/lab/realeval/$(2).conf \
        $(wildcard tools/lab/kidnap/$(2)-search.conf) \
        $(if $(wildcard $(DATA)/raw/$(1)-raw.log.gz),$(if $(wildcard $(DATA)/raw/$(1)-groundtruth.tum),\
             $(EVAL_OUT)/input/$(1)_$(2)_every.lcmlog))
	$$(Q)$$(KIDNAP_ENV) sh tools/lab/kidnap/run_row.sh real $(1) $(2)
endef

$(foreach w,$(KIDNAP_WORLDS),$(eval $(call kidnap_sim,$(w))) \
    $(foreach s,$(KIDNAP_TOUR_SEEDS),$(eval $(call kidnap_tour,$(w),$(s)))))
$(foreach b,$(BUILDINGS),$(foreach i,laser sonar,$(eval $(call kidnap_real,$(b),$(i)))))
