# tests/eval-harness/hl_eval.mk - hl-eval, the harness that scores and compares houghlocd's
# recorded output (not installed; houghloc-eval, tools/eval, is the installed scorer): the
# goldens' text streams (tests/golden), the integration tests' extractions, splits and
# garbled logs, make demo's score, the laboratory's scripts. `make` builds it with the
# product, as $(BUILD)/bin/hl-eval. It reads logs with tools/eval's runlog.c (shared with
# houghloc-eval and houghloc-map) and moves the simulator's truth into the map frame with
# truth_frame.c (shared with houghloc-map and houghloc-console).

BINS += $(BUILD)/bin/hl-eval

HL_EVAL_OBJS := $(call obj,tests/eval-harness/eval.c tests/eval-harness/latency.c \
                           tests/eval-harness/golden_text.c tools/eval/runlog.c \
                           tools/eval/truth_frame.c)

$(call obj,$(wildcard tests/eval-harness/*.c)): CPPFLAGS += -Itools/eval

$(BUILD)/bin/hl-eval: $(HL_EVAL_OBJS) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(HL_EVAL_OBJS) $(BUS_LIB) $(BUS_LDLIBS)
