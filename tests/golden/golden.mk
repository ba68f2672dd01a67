# tests/golden/golden.mk - the goldens (tests/golden/check.sh, tests/golden/README.md):
# houghlocd's POSE streams for each sensor profile (and loop closure) on the simulated
# logs, and the SONAR and ODOMETRY it publishes from a captured ARCOS byte stream, kept as
# text (one line per message, every field: hl-eval text); make test compares them byte
# for byte.
#
#   make golden          regenerate them (only when a change of output is intended: commit
#                        them with the change, the commit message saying why the output
#                        changed) and print which changed
#   make golden-capture  record tests/golden/arcos.capture anew with houghloc-sim (only when
#                        the robot's side of the protocol changed; then make golden)
# Their inputs: logs/*.lcmlog (make logs) and tests/golden/arcos.capture.

INTEGRATION_TESTS += tests/golden/check.sh tests/golden/bad_capture.sh

.PHONY: golden golden-capture
golden: $(BUILD)/bin/houghlocd $(BUILD)/bin/hl-eval
	$(Q)BUILD=$(BUILD) sh tests/golden/check.sh --regenerate

golden-capture: $(BUILD)/bin/houghlocd $(BUILD)/bin/houghloc-sim
	$(Q)BUILD=$(BUILD) sh tests/golden/capture.sh
