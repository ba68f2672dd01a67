# The watchdog integration test: houghlocd under a fake systemd (NOTIFY_SOCKET, a python3
# listener), READY=1, WATCHDOG=1 every 100 ms, none while the loop is stopped (SIGSTOP) or
# blocked on its own log, STOPPING=1; it needs houghlocd, which `make all` builds.
INTEGRATION_TESTS += tests/integration/test_watchdog.sh
