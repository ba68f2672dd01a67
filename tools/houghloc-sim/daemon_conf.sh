# daemon_conf.sh - houghlocd's configuration for driving houghloc-sim in its built-in lab
# (POSIX sh, sourced): the live-robot tests (tests/integration/robot_lib.sh) and the link
# trial write it with write_lab_robot_conf. (make demo and the README's recipe need no
# file: tools/demo/demo.sh.)

# write_lab_robot_conf FILE X_M Y_M HEADING_DEG: houghlocd on the LCM network $URL, the
# robot houghloc-sim at tcp:127.0.0.1:$PORT, starting at the pose given (the lab's frame:
# tests name places and compare true poses in it), fenced to the lab; the robot profile
# houghloc-sim carries the calibration hl-calibrate measures for the simulated transducers.
write_lab_robot_conf() {
    cat >"$1" <<CONF
[lcm]
url = $URL
[start]
x_m = $2
y_m = $3
heading_deg = $4
[fence]
rect = -1,-1,11,9
[robot]
link = tcp:127.0.0.1:$PORT
profile = houghloc-sim
CONF
}
