# tools/lab/realeval/realeval.mk - make eval-real: houghlocd on the five real buildings
# (docs/results/real-buildings.md). Included by tools/lab/lab.mk.
#
#   make -j2 eval-real                       all five buildings, two at a time
#   make eval-real DATA=/elsewhere           the data folder (holding raw/); default
#                                            ../shared/data
#   make eval-real BUILDINGS='intel aces'    some buildings only
#
# Every (building, input, mode, selection, start) is one file target, a row of the table
# in EVAL_OUT/rows/, made by tools/lab/realeval/run_one.sh: odometry alone (houghloc-eval
# --odometry; one row, start origin), or a replay through houghlocd's batch path (the
# daemon the robot runs, configured by tools/lab/realeval/INPUT.conf, INPUT-paper.conf
# for the paper mode, INPUT-loops.conf for the improved mode with loop closure) scored by
# houghloc-eval, from each of four starts: the robot's own
# frame (origin, the daemon's default), that frame turned 30 and 45 degrees, and the
# first true pose (truth, for reference). Imports are cached in EVAL_OUT/input/, one per
# (building, input, selection), shared by the modes and starts. report.sh then writes
# EVAL_OUT/real.tsv and real.md (the origin rows beside the peers' figures from
# BASELINES, every start and their spread below); run_one.sh map draws EVAL_OUT/B.png and
# B-sonar.png, the final maps of the improved mode from the origin on every laser scan and
# every pseudo-sonar scan with their paths and the true path aligned into their frames. A row is remade when its import, the
# programs, the configuration or the script change.

DATA      ?= ../shared/data
BASELINES ?= $(DATA)/../BASELINES.md
BUILDINGS ?= intel aces freiburg-079 csail freiburg-101
EVAL_OUT  ?= $(BUILD)/eval

REALEVAL_INPUTS     := laser sonar
REALEVAL_MODES      := odometry paper improved loops
REALEVAL_SELECTIONS := every moved
REALEVAL_STARTS     := origin turned30 turned45 truth
REALEVAL_PROGS := $(BUILD)/bin/houghlocd $(BUILD)/bin/hl-eval $(BUILD)/bin/houghloc-eval \
                  $(BUILD)/bin/houghloc-import-carmen
# realeval_starts MODE: the starts a mode runs from (odometry: its one row).
realeval_starts = $(if $(filter odometry,$(1)),origin,$(REALEVAL_STARTS))
REALEVAL_ROWS := $(foreach b,$(BUILDINGS),$(foreach i,$(REALEVAL_INPUTS),\
                   $(foreach m,$(REALEVAL_MODES),$(foreach s,$(REALEVAL_SELECTIONS),\
                     $(foreach t,$(call realeval_starts,$(m)),\
                       $(EVAL_OUT)/rows/$(b)_$(i)_$(m)_$(s)_$(t).tsv)))))
REALEVAL_PNGS := $(patsubst %,$(EVAL_OUT)/%.png,$(BUILDINGS)) \
                 $(patsubst %,$(EVAL_OUT)/%-sonar.png,$(BUILDINGS))
REALEVAL_ENV = BUILD='$(BUILD)' DATA='$(DATA)' EVAL_OUT='$(EVAL_OUT)' \
               REALEVAL_TOTAL=$(words $(REALEVAL_ROWS))

LAB_INTEGRATION_TESTS += tools/lab/tests/test_realeval.sh

.PHONY: eval-real eval-real-outputs

# deps first (as make bench and make experiments), then the rows in parallel under -j.
eval-real: deps
	$(Q)$(MAKE) --no-print-directory eval-real-outputs

eval-real-outputs: $(EVAL_OUT)/real.tsv $(EVAL_OUT)/real.md $(REALEVAL_PNGS)
	@echo "eval-real: $(EVAL_OUT)/real.tsv, $(EVAL_OUT)/real.md and $(words $(REALEVAL_PNGS)) maps" >&2

# A data file that is missing: one line naming it, rather than make's "No rule".
$(DATA)/raw/%:
	@echo "eval-real: $*: missing in $(DATA)/raw (set DATA=, the folder holding raw/)" >&2
	@exit 1

# realeval_import B INPUT SELECTION
define realeval_import
$(EVAL_OUT)/input/$(1)_$(2)_$(3).lcmlog: $(DATA)/raw/$(1)-raw.log.gz \
        $(DATA)/raw/$(1)-groundtruth.tum $(BUILD)/bin/houghloc-import-carmen \
        tools/lab/realeval/run_one.sh
	$$(Q)$$(REALEVAL_ENV) sh tools/lab/realeval/run_one.sh import $(1) $(2) $(3)
endef

# realeval_cell B INPUT MODE SELECTION START
define realeval_cell
$(EVAL_OUT)/rows/$(1)_$(2)_$(3)_$(4)_$(5).tsv: $(EVAL_OUT)/input/$(1)_$(2)_$(4).lcmlog \
        $(REALEVAL_PROGS) tools/lab/realeval/$(2).conf tools/lab/realeval/$(2)-paper.conf \
        tools/lab/realeval/$(2)-loops.conf \
        tools/lab/realeval/run_one.sh
	$$(Q)$$(REALEVAL_ENV) sh tools/lab/realeval/run_one.sh cell $(1) $(2) $(4) $(3) $(5)
endef

$(foreach b,$(BUILDINGS),$(foreach i,$(REALEVAL_INPUTS),$(foreach s,$(REALEVAL_SELECTIONS),\
    $(eval $(call realeval_import,$(b),$(i),$(s))))))
$(foreach b,$(BUILDINGS),$(foreach i,$(REALEVAL_INPUTS),$(foreach m,$(REALEVAL_MODES),\
    $(foreach s,$(REALEVAL_SELECTIONS),$(foreach t,$(call realeval_starts,$(m)),\
      $(eval $(call realeval_cell,$(b),$(i),$(m),$(s),$(t))))))))

# The final map of the origin run with its POSE path and the true path aligned into it.
$(EVAL_OUT)/%.png: $(EVAL_OUT)/rows/%_laser_improved_every_origin.tsv $(BUILD)/bin/houghloc-map \
        tools/lab/realeval/run_one.sh
	$(Q)$(REALEVAL_ENV) sh tools/lab/realeval/run_one.sh map $*
$(EVAL_OUT)/%-sonar.png: $(EVAL_OUT)/rows/%_sonar_improved_every_origin.tsv \
        $(BUILD)/bin/houghloc-map tools/lab/realeval/run_one.sh
	$(Q)$(REALEVAL_ENV) sh tools/lab/realeval/run_one.sh map $* sonar

$(EVAL_OUT)/real.tsv: $(REALEVAL_ROWS) tools/lab/realeval/report.sh
	$(Q)sh tools/lab/realeval/report.sh tsv '$(EVAL_OUT)' '$(BUILDINGS)' >$@.tmp && mv $@.tmp $@ || \
	{ rm -f $@.tmp; exit 1; }

$(EVAL_OUT)/real.md: $(EVAL_OUT)/real.tsv tools/lab/realeval/report.sh
	$(Q)sh tools/lab/realeval/report.sh md '$(EVAL_OUT)' '$(BUILDINGS)' '$(BASELINES)' \
	    >$@.tmp && mv $@.tmp $@ || { rm -f $@.tmp; exit 1; }
