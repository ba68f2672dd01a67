# tools/eval/eval.mk - hl-eval: scores houghlocd's output against ground truth (make demo)
# and extracts channels for the replay-determinism tests.

BINS += $(BUILD)/bin/hl-eval

$(BUILD)/bin/hl-eval: $(call obj,tools/eval/eval.c) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $(call obj,tools/eval/eval.c) $(BUS_LIB) $(BUS_LDLIBS)
