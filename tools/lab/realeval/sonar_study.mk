# tools/lab/realeval/sonar_study.mk - hl-sonar-study: where the pseudo-sonar ring's error
# comes from (tools/lab/realeval/sonar_study.sh; docs/results/real-buildings.md). It reads
# the imports with the experiments' log reader (tools/lab/experiments/dataset.hpp).

SONAR_STUDY_OBJS := $(call obj,tools/lab/realeval/sonar_study.cpp tools/lab/experiments/dataset.cpp)

LAB_BINS += $(BUILD)/bin/hl-sonar-study

$(call obj,tools/lab/realeval/sonar_study.cpp): $(BUILD)/obj/%.o: %.cpp | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CXX     $<"
	$(Q)$(CXX) $(CPPFLAGS) -Itools/lab/experiments $(PKG_CFLAGS) $(CXXFLAGS) -c -o $@ $<

$(BUILD)/bin/hl-sonar-study: $(SONAR_STUDY_OBJS) $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CXX) -o $@ $(SONAR_STUDY_OBJS) $(BUS_LIB) $(BUS_LDLIBS)
