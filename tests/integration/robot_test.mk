# The live-robot integration test: houghlocd drives houghloc-sim over TCP on loopback
# (destinations, a SIGKILLed and restarted robot, injected faults, the serial transport's
# errors, and a replay of the live log); it needs houghlocd, houghloc-sim, houghloc-goto
# and hl-eval, which `make all` builds.
INTEGRATION_TESTS += tests/integration/test_robot.sh
# The kidnapped robot: houghloc-sim teleports the robot; the daemon notices, is lost, finds
# it again within three soundings (docs/results/relocalization.md).
INTEGRATION_TESTS += tests/integration/test_lost.sh
# Driving that can be trusted: the sonar's safety stop at a wall and at a chair leg, a
# path planned round a box, STOP from houghloc-ctl and from Ctrl-C on houghloc-goto, and
# the robot stopped when the daemon stalls or dies (tests/integration/worlds/chairleg.world).
INTEGRATION_TESTS += tests/integration/test_drive.sh
# A one-way link loss: houghloc-sim falls silent but still obeys (--mute-after); the daemon
# sends STOP before it closes the link, and the destination fails saying so.
INTEGRATION_TESTS += tests/integration/test_link_loss.sh
