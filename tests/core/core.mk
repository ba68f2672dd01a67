# tests/core/core.mk - link options of the core's tests that need them (the link rule:
# the top Makefile's $(BUILD)/tests/core/%, which adds TEST_LDFLAGS).
#
# test_slam_onepass counts the tracker's stages wherever in the core they are called:
# each is wrapped at link time (__wrap_NAME counts, then calls __real_NAME).
ONEPASS_WRAPPED := hl_scan_check hl_echo_correct hl_echo_correct_valid hl_loc_run \
                   hl_loc_run_valid hl_reloc_run_scans hl_reloc_run_scans_valid
$(BUILD)/tests/core/test_slam_onepass: TEST_LDFLAGS := $(foreach f,$(ONEPASS_WRAPPED),-Wl,--wrap=$(f))
