# tools/eval/eval.mk - hl-eval: scores houghlocd's output against ground truth (make demo)
# and extracts channels for the replay-determinism tests. Its log reading (runlog.c) is
# shared with houghloc-eval (houghloc_eval.mk) and houghloc-map (tools/map/map.mk), its
# move of the simulator's truth into the daemon's map frame (truth_frame.c) with
# houghloc-map and houghloc-console (tools/console/console.mk).

BINS += $(BUILD)/bin/hl-eval

RUNLOG_OBJ := $(BUILD)/obj/tools/eval/runlog.o
TRUTH_FRAME_OBJ := $(BUILD)/obj/tools/eval/truth_frame.o

HL_EVAL_OBJS := $(call obj,tools/eval/eval.c tools/eval/latency.c) $(RUNLOG_OBJ) $(TRUTH_FRAME_OBJ)

$(BUILD)/bin/hl-eval: $(HL_EVAL_OBJS) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(HL_EVAL_OBJS) $(BUS_LIB) $(BUS_LDLIBS)
