# tools/lab/realeval/realeval.mk - make eval-real: houghlocd on the five real buildings
# (docs/results/real-buildings.md). Included by tools/lab/lab.mk.
#
#   make -j2 eval-real                       all five buildings, two at a time
#   make eval-real DATA=/elsewhere           the data folder (holding raw/); default
#                                            ../shared/data
#   make eval-real BUILDINGS='intel aces'    some buildings only
#
# Every (building, input, mode, selection) is one file target, a row of the table in
# EVAL_OUT/rows/, made by tools/lab/realeval/run_one.sh: odometry alone (houghloc-eval
# --odometry), or a replay through houghlocd's batch path (the daemon the robot runs,
# configured by tools/lab/realeval/INPUT.conf, or INPUT-paper.conf for the paper mode)
# scored by houghloc-eval. Imports are cached in EVAL_OUT/input/, one per (building, input,
# selection), shared by the modes. report.sh then writes EVAL_OUT/real.tsv and real.md
# (the peers' figures from BASELINES beside ours); houghloc-map draws EVAL_OUT/B.png, the
# final map of the improved mode on every laser scan with the true and estimated paths.
# A row is remade when its import, the programs, the configuration or the script change.

DATA      ?= ../shared/data
BASELINES ?= $(DATA)/../BASELINES.md
BUILDINGS ?= intel aces freiburg-079 csail freiburg-101
EVAL_OUT  ?= $(BUILD)/eval

REALEVAL_INPUTS     := laser sonar
REALEVAL_MODES      := odometry paper improved
REALEVAL_SELECTIONS := every moved
REALEVAL_PROGS := $(BUILD)/bin/houghlocd $(BUILD)/bin/hl-eval $(BUILD)/bin/houghloc-eval \
                  $(BUILD)/bin/houghloc-import-carmen
REALEVAL_ROWS := $(foreach b,$(BUILDINGS),$(foreach i,$(REALEVAL_INPUTS),\
                   $(foreach m,$(REALEVAL_MODES),$(foreach s,$(REALEVAL_SELECTIONS),\
                     $(EVAL_OUT)/rows/$(b)_$(i)_$(m)_$(s).tsv))))
REALEVAL_PNGS := $(patsubst %,$(EVAL_OUT)/%.png,$(BUILDINGS))
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

# realeval_cell B INPUT MODE SELECTION
define realeval_cell
$(EVAL_OUT)/rows/$(1)_$(2)_$(3)_$(4).tsv: $(EVAL_OUT)/input/$(1)_$(2)_$(4).lcmlog \
        $(REALEVAL_PROGS) tools/lab/realeval/$(2).conf tools/lab/realeval/$(2)-paper.conf \
        tools/lab/realeval/run_one.sh
	$$(Q)$$(REALEVAL_ENV) sh tools/lab/realeval/run_one.sh cell $(1) $(2) $(4) $(3)
endef

$(foreach b,$(BUILDINGS),$(foreach i,$(REALEVAL_INPUTS),$(foreach s,$(REALEVAL_SELECTIONS),\
    $(eval $(call realeval_import,$(b),$(i),$(s))))))
$(foreach b,$(BUILDINGS),$(foreach i,$(REALEVAL_INPUTS),$(foreach m,$(REALEVAL_MODES),\
    $(foreach s,$(REALEVAL_SELECTIONS),$(eval $(call realeval_cell,$(b),$(i),$(m),$(s)))))))

# The final map (the run's map file) with its POSE path and the true path of its input.
$(EVAL_OUT)/%.png: $(EVAL_OUT)/rows/%_laser_improved_every.tsv $(BUILD)/bin/houghloc-map
	$(Q)r=$(EVAL_OUT)/runs/$*_laser_improved_every; \
	$(BUILD)/bin/houghloc-map --trajectory $$r/out.lcmlog \
	    --trajectory $(EVAL_OUT)/input/$*_laser_every.lcmlog $$r/map.hlmap $$r/map \
	    >$$r/map.err 2>&1 && cp $$r/map.png $@ || \
	{ echo "eval-real: $* laser every improved: map failed: $$(tail -n 1 $$r/map.err)" >&2; \
	  exit 1; }

$(EVAL_OUT)/real.tsv: $(REALEVAL_ROWS) tools/lab/realeval/report.sh
	$(Q)sh tools/lab/realeval/report.sh tsv '$(EVAL_OUT)' '$(BUILDINGS)' >$@.tmp && mv $@.tmp $@ || \
	{ rm -f $@.tmp; exit 1; }

$(EVAL_OUT)/real.md: $(EVAL_OUT)/real.tsv tools/lab/realeval/report.sh
	$(Q)sh tools/lab/realeval/report.sh md '$(EVAL_OUT)' '$(BUILDINGS)' '$(BASELINES)' \
	    >$@.tmp && mv $@.tmp $@ || { rm -f $@.tmp; exit 1; }
