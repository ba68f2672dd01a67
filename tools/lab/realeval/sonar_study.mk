# tools/lab/realeval/sonar_study.mk - hl-sonar-study: where the pseudo-sonar ring's error
# comes from (tools/lab/realeval/sonar_study.sh; docs/results/real-buildings.md).

LAB_BINS += $(BUILD)/bin/hl-sonar-study

$(BUILD)/bin/hl-sonar-study: $(call obj,tools/lab/realeval/sonar_study.c) $(CORE_LIB)
	@mkdir -p $(@D)
	$(Q)$(CXX) -o $@ $^ $(SYS_LIBS)
