# tests/fuzz/fuzz.mk - fuzzing kept in the project (docs/results/reliability.md).
#
#   make fuzz                   build every target with clang, libFuzzer, ASan and UBSan
#                               into $(BUILD)/fuzz/ and run each for FUZZ_SECONDS (30);
#                               one line per target "fuzz NAME: execs=E crashes=K", then
#                               "fuzz targets=T execs=E crashes=K"; fails on any crash.
#   make fuzz FUZZ_RUNS=10000000   each target until that many executions instead
#   make -j2 fuzz               two targets at a time
#   make test / make unit-test  replays tests/fuzz/corpus/NAME and tests/fuzz/regress/NAME
#                               through each target built with gcc under ASan and UBSan
#                               ($(BUILD)/tests/fuzz/replay_NAME, in TEST_BINS): no clang.
#
# The targets link the very code the programs link: the clang build compiles the same
# sources as the libraries of src/*/*.mk (and tools/carmen's parser, tools/sim's world
# parser) with coverage instrumentation; the replays link the sanitized libraries that
# the unit tests link. This file is read before tools/*/*.mk (the top Makefile sorts the
# includes), so the carmen and simulator objects are named by path.

# ---- the targets, by the libraries they need ----------------------------------------
FUZZ_ROBOT_NAMES  := arcos rlink
FUZZ_BUS_NAMES    := bus_scan bus_odometry bus_pose bus_map bus_status bus_destination \
                     bus_command bus_reply logcheck
FUZZ_DAEMON_NAMES := config mapstore keyfile cycle
FUZZ_CARMEN_NAMES := carmen carmen_reader
FUZZ_SIM_NAMES    := world
FUZZ_NAMES := $(FUZZ_ROBOT_NAMES) $(FUZZ_BUS_NAMES) $(FUZZ_DAEMON_NAMES) \
              $(FUZZ_CARMEN_NAMES) $(FUZZ_SIM_NAMES)
# The console's POST body parser (tools/console/destreq.c): pure, the core's angles only.
FUZZ_CONSOLE_NAMES := console_body
FUZZ_NAMES += $(FUZZ_CONSOLE_NAMES)

# A new tests/fuzz/fuzz_X.c must be put in a group above, or it would silently not run.
FUZZ_UNLISTED := $(filter-out $(FUZZ_NAMES),$(patsubst tests/fuzz/fuzz_%,%,$(basename \
                 $(wildcard tests/fuzz/fuzz_*.c tests/fuzz/fuzz_*.cpp))))
$(if $(FUZZ_UNLISTED),$(error tests/fuzz/fuzz.mk: put fuzz_$(firstword $(FUZZ_UNLISTED)) in a group))

# (The libFuzzer build compiles every layer's sources with these: both internal folders.)
FUZZ_INC := -Itests/fuzz -Isrc/daemon -Itools/carmen -Itools/sim $(CORE_INTERNAL_INC) \
            $(DAEMON_INTERNAL_INC)
FUZZ_SIM_ASAN_LIB := $(BUILD)/lib/libhoughloc_sim_asan.a
FUZZ_CARMEN_ASAN_OBJ := $(BUILD)/asan/tools/carmen/carmen_log.o

# ---- replays: gcc, ASan + UBSan, run by make test ------------------------------------
fuzz_replay = $(patsubst %,$(BUILD)/tests/fuzz/replay_%,$(1))
FUZZ_REPLAYS := $(call fuzz_replay,$(FUZZ_NAMES))
TEST_BINS += $(FUZZ_REPLAYS)

FUZZ_MEMFILE_ASAN := $(BUILD)/asan/tests/fuzz/memfile.o
FUZZ_ASAN_FLAGS = $(CPPFLAGS) $(FUZZ_INC) $(PKG_CFLAGS) $(DAEMON_CFLAGS)

$(BUILD)/asan/tests/fuzz/%.o: tests/fuzz/%.c | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(FUZZ_ASAN_FLAGS) $(CFLAGS) $(SAN) -c -o $@ $<
$(BUILD)/asan/tests/fuzz/%.o: tests/fuzz/%.cpp | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CXX-SAN $<"
	$(Q)$(CXX) $(FUZZ_ASAN_FLAGS) $(CXXFLAGS) $(SAN) -c -o $@ $<
# One replay main per target: the folders it replays with no argument are compiled in,
# relative to the repository root (where tests/run-unit.sh runs).
# A static pattern rule: a plain one, whose prerequisite does not depend on the stem,
# would also offer to make any replay_main-X.o (make then tries it for the .d files).
$(patsubst %,$(BUILD)/asan/tests/fuzz/replay_main-%.o,$(FUZZ_NAMES)): \
        $(BUILD)/asan/tests/fuzz/replay_main-%.o: tests/fuzz/replay_main.c
	@mkdir -p $(@D)
	@echo "  CC-SAN  $< ($*)"
	$(Q)$(CC) $(FUZZ_ASAN_FLAGS) $(CFLAGS) $(SAN) -DHL_FUZZ_NAME='"$*"' \
	    -DHL_FUZZ_CORPUS='"tests/fuzz/corpus/$*"' -DHL_FUZZ_REGRESS='"tests/fuzz/regress/$*"' \
	    -c -o $@ $<

# In a static pattern rule's prerequisites '%' is the target's name; in its recipe, $*.
FUZZ_REPLAY_PREREQS := $(BUILD)/asan/tests/fuzz/fuzz_%.o $(BUILD)/asan/tests/fuzz/replay_main-%.o \
                       $(FUZZ_MEMFILE_ASAN)
FUZZ_REPLAY_OBJS = $(BUILD)/asan/tests/fuzz/fuzz_$*.o $(BUILD)/asan/tests/fuzz/replay_main-$*.o \
                   $(FUZZ_MEMFILE_ASAN)

$(call fuzz_replay,$(FUZZ_ROBOT_NAMES)): $(BUILD)/tests/fuzz/replay_%: $(FUZZ_REPLAY_PREREQS) \
        $(ROBOT_ASAN_LIB) $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -o $@ $(FUZZ_REPLAY_OBJS) $(ROBOT_ASAN_LIB) $(CORE_ASAN_LIB) $(SYS_LIBS)
$(call fuzz_replay,$(FUZZ_BUS_NAMES)): $(BUILD)/tests/fuzz/replay_%: $(FUZZ_REPLAY_PREREQS) \
        $(BUS_ASAN_LIB) $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -o $@ $(FUZZ_REPLAY_OBJS) $(BUS_ASAN_LIB) $(CORE_ASAN_LIB) $(PKG_LIBS) \
	    $(SODIUM_LIBS) $(SYS_LIBS)
$(call fuzz_replay,$(FUZZ_DAEMON_NAMES)): $(BUILD)/tests/fuzz/replay_%: $(FUZZ_REPLAY_PREREQS) \
        $(DAEMON_ASAN_LIB) $(ROBOT_ASAN_LIB) $(STORE_ASAN_LIB) $(BUS_ASAN_LIB) $(LCM_LIB) $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -o $@ $(FUZZ_REPLAY_OBJS) $(DAEMON_ASAN_LIB) $(DAEMON_ASAN_LDLIBS)
$(call fuzz_replay,$(FUZZ_CARMEN_NAMES)): $(BUILD)/tests/fuzz/replay_%: $(FUZZ_REPLAY_PREREQS) \
        $(FUZZ_CARMEN_ASAN_OBJ)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -o $@ $(FUZZ_REPLAY_OBJS) $(FUZZ_CARMEN_ASAN_OBJ) $(ZLIB_LIBS) $(SYS_LIBS)
$(call fuzz_replay,$(FUZZ_SIM_NAMES)): $(BUILD)/tests/fuzz/replay_%: $(FUZZ_REPLAY_PREREQS) \
        $(FUZZ_SIM_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CXX) $(SAN) -o $@ $(FUZZ_REPLAY_OBJS) $(FUZZ_SIM_ASAN_LIB) $(SYS_LIBS)
# console_body: tools/console's parser, named by path (console.mk is read after this file).
FUZZ_CONSOLE_ASAN_OBJ := $(BUILD)/asan/tools/console/destreq.o
$(BUILD)/asan/tests/fuzz/fuzz_console_body.o: FUZZ_INC += -Itools/console
$(call fuzz_replay,$(FUZZ_CONSOLE_NAMES)): $(BUILD)/tests/fuzz/replay_%: $(FUZZ_REPLAY_PREREQS) \
        $(FUZZ_CONSOLE_ASAN_OBJ) $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -o $@ $(FUZZ_REPLAY_OBJS) $(FUZZ_CONSOLE_ASAN_OBJ) $(CORE_ASAN_LIB) $(SYS_LIBS)

# ---- libFuzzer builds: clang ---------------------------------------------------------
FUZZ_OUT := $(BUILD)/fuzz
FUZZ_CC  ?= clang
FUZZ_CXX ?= clang++
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZ_OPT ?= -O1 -g
FUZZ_CPPFLAGS = $(CPPFLAGS) $(FUZZ_INC) $(PKG_CFLAGS) $(DAEMON_CFLAGS)
FUZZ_CFLAGS   = -std=c11 $(CWARN) $(FUZZ_OPT) $(FUZZ_SAN) -fsanitize=fuzzer-no-link
FUZZ_CXXFLAGS = -std=c++17 $(WARN) $(FUZZ_OPT) $(FUZZ_SAN) -fsanitize=fuzzer-no-link $(EIGEN_CFLAGS)
FUZZ_LDFLAGS  = -fsanitize=fuzzer $(FUZZ_SAN)

fuzz_obj = $(patsubst %.c,$(FUZZ_OUT)/obj/%.o,$(patsubst %.cpp,$(FUZZ_OUT)/obj/%.o,$(1)))

# The same sources as the libraries (generated ones included), instrumented.
FUZZ_CORE_LIB   := $(FUZZ_OUT)/lib/libcore.a
FUZZ_ROBOT_LIB  := $(FUZZ_OUT)/lib/librobot.a
FUZZ_BUS_LIB    := $(FUZZ_OUT)/lib/libbus.a
FUZZ_DAEMON_LIB := $(FUZZ_OUT)/lib/libdaemon.a
FUZZ_CARMEN_OBJ := $(call fuzz_obj,tools/carmen/carmen_log.c)
FUZZ_SIM_OBJS   := $(call fuzz_obj,tools/sim/world.cpp $(BUILD)/gen/sim_lab_world.cpp)
FUZZ_MEMFILE    := $(call fuzz_obj,tests/fuzz/memfile.c)

$(FUZZ_CORE_LIB): $(call fuzz_obj,$(CORE_SRCS) $(SOLVE_SRCS) $(TRIG_SRC))
$(FUZZ_ROBOT_LIB): $(call fuzz_obj,$(ROBOT_SRCS))
$(FUZZ_BUS_LIB): $(call fuzz_obj,$(BUS_SRCS) $(LCM_C_SRCS))
$(FUZZ_DAEMON_LIB): $(call fuzz_obj,$(DAEMON_LIB_SRCS) $(STORE_SRCS))
$(FUZZ_OUT)/lib/%.a:
	@mkdir -p $(@D)
	$(Q)rm -f $@ && ar rcs $@ $^

$(FUZZ_OUT)/obj/%.o: %.c | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CC-FUZZ $<"
	$(Q)$(FUZZ_CC) $(FUZZ_CPPFLAGS) $(FUZZ_CFLAGS) -c -o $@ $<
$(FUZZ_OUT)/obj/%.o: %.cpp | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CXX-FUZZ $<"
	$(Q)$(FUZZ_CXX) $(FUZZ_CPPFLAGS) $(FUZZ_CXXFLAGS) -c -o $@ $<
# Generated LCM code is not ours to fix: no -Werror extras, as in the top Makefile.
$(call fuzz_obj,$(LCM_C_SRCS)): FUZZ_CFLAGS = -std=c11 $(FUZZ_OPT) $(FUZZ_SAN) -fsanitize=fuzzer-no-link
# The vote raster's passes (blur, peak search) visit every cell with the same few
# branches whatever the input: instrumented, they took nearly all of fuzz_cycle's time
# and told libFuzzer nothing. They keep ASan and UBSan, not coverage.
$(call fuzz_obj,src/core/blur.c src/core/peak.c): FUZZ_CFLAGS = -std=c11 $(CWARN) $(FUZZ_OPT) $(FUZZ_SAN)

fuzz_bin = $(patsubst %,$(FUZZ_OUT)/fuzz_%,$(1))
FUZZ_BINS := $(call fuzz_bin,$(FUZZ_NAMES))
FUZZ_OBJ_PREREQS := $(FUZZ_OUT)/obj/tests/fuzz/fuzz_%.o $(FUZZ_MEMFILE)
FUZZ_OBJS = $(FUZZ_OUT)/obj/tests/fuzz/fuzz_$*.o $(FUZZ_MEMFILE)

$(call fuzz_bin,$(FUZZ_ROBOT_NAMES)): $(FUZZ_OUT)/fuzz_%: $(FUZZ_OBJ_PREREQS) $(FUZZ_ROBOT_LIB) \
        $(FUZZ_CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD-FUZZ $@"
	$(Q)$(FUZZ_CC) $(FUZZ_LDFLAGS) -o $@ $(FUZZ_OBJS) $(FUZZ_ROBOT_LIB) $(FUZZ_CORE_LIB) $(SYS_LIBS)
$(call fuzz_bin,$(FUZZ_BUS_NAMES)): $(FUZZ_OUT)/fuzz_%: $(FUZZ_OBJ_PREREQS) $(FUZZ_BUS_LIB) \
        $(FUZZ_CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD-FUZZ $@"
	$(Q)$(FUZZ_CC) $(FUZZ_LDFLAGS) -o $@ $(FUZZ_OBJS) $(FUZZ_BUS_LIB) $(FUZZ_CORE_LIB) \
	    $(PKG_LIBS) $(SODIUM_LIBS) $(SYS_LIBS)
$(call fuzz_bin,$(FUZZ_DAEMON_NAMES)): $(FUZZ_OUT)/fuzz_%: $(FUZZ_OBJ_PREREQS) $(FUZZ_DAEMON_LIB) \
        $(FUZZ_ROBOT_LIB) $(FUZZ_BUS_LIB) $(FUZZ_CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD-FUZZ $@"
	$(Q)$(FUZZ_CC) $(FUZZ_LDFLAGS) -o $@ $(FUZZ_OBJS) $(FUZZ_DAEMON_LIB) $(FUZZ_ROBOT_LIB) \
	    $(FUZZ_BUS_LIB) $(FUZZ_CORE_LIB) $(DAEMON_LIBS) $(PKG_LIBS) $(SODIUM_LIBS) $(SYS_LIBS)
$(call fuzz_bin,$(FUZZ_CARMEN_NAMES)): $(FUZZ_OUT)/fuzz_%: $(FUZZ_OBJ_PREREQS) $(FUZZ_CARMEN_OBJ)
	@mkdir -p $(@D)
	@echo "  LD-FUZZ $@"
	$(Q)$(FUZZ_CC) $(FUZZ_LDFLAGS) -o $@ $(FUZZ_OBJS) $(FUZZ_CARMEN_OBJ) $(ZLIB_LIBS) $(SYS_LIBS)
$(call fuzz_bin,$(FUZZ_SIM_NAMES)): $(FUZZ_OUT)/fuzz_%: $(FUZZ_OUT)/obj/tests/fuzz/fuzz_%.o \
        $(FUZZ_MEMFILE) $(FUZZ_SIM_OBJS)
	@mkdir -p $(@D)
	@echo "  LD-FUZZ $@"
	$(Q)$(FUZZ_CXX) $(FUZZ_LDFLAGS) -o $@ $^ $(SYS_LIBS)
FUZZ_CONSOLE_OBJ := $(call fuzz_obj,tools/console/destreq.c)
$(FUZZ_OUT)/obj/tests/fuzz/fuzz_console_body.o: FUZZ_INC += -Itools/console
$(call fuzz_bin,$(FUZZ_CONSOLE_NAMES)): $(FUZZ_OUT)/fuzz_%: $(FUZZ_OBJ_PREREQS) $(FUZZ_CONSOLE_OBJ) \
        $(FUZZ_CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD-FUZZ $@"
	$(Q)$(FUZZ_CC) $(FUZZ_LDFLAGS) -o $@ $(FUZZ_OBJS) $(FUZZ_CONSOLE_OBJ) $(FUZZ_CORE_LIB) $(SYS_LIBS)

# ---- make fuzz -----------------------------------------------------------------------
FUZZ_SECONDS ?= 30
FUZZ_RUNS    ?=
FUZZ_TIMEOUT ?= 10
FUZZ_FLAGS   ?=

.PHONY: fuzz fuzz-build fuzz-deps
fuzz-deps:
	$(Q)sh tools/build/install-deps.sh
	$(Q)sh tools/build/install-fuzz-deps.sh

fuzz-build: $(FUZZ_BINS)

# Not phony (make skips the pattern search for phony targets); no such file is made.
fuzz-run-%: $(FUZZ_OUT)/fuzz_%
	$(Q)FUZZ_FLAGS="$(FUZZ_FLAGS)" sh tests/fuzz/fuzz.sh run $* $(FUZZ_OUT) "$(FUZZ_SECONDS)" \
	    "$(FUZZ_RUNS)" "$(FUZZ_TIMEOUT)"

fuzz: fuzz-deps
	$(Q)$(MAKE) --no-print-directory fuzz-build
	$(Q)$(MAKE) --no-print-directory $(addprefix fuzz-run-,$(FUZZ_NAMES))
	$(Q)sh tests/fuzz/fuzz.sh summary $(FUZZ_OUT) $(FUZZ_NAMES)

# ---- the committed seeds (tests/fuzz/corpus/), remade only by hand ---------------------
#   make fuzz-seeds    rewrites tests/fuzz/corpus/ from the encoders, logs/, a short
#                      houghlocd replay, the configuration and world files
#                      (tests/fuzz/make_seeds.sh)
$(BUILD)/tests/fuzz/gen_seeds: $(BUILD)/obj/tests/fuzz/gen_seeds.o $(ROBOT_LIB) $(STORE_LIB) \
        $(BUS_LIB) $(LCM_LIB) $(CORE_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $< $(ROBOT_LIB) $(STORE_LIB) $(STORE_LDLIBS) $(SODIUM_LIBS)

.PHONY: fuzz-seeds
fuzz-seeds: $(BUILD)/tests/fuzz/gen_seeds $(BUILD)/bin/houghlocd
	$(Q)BUILD=$(BUILD) sh tests/fuzz/make_seeds.sh
