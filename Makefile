# houghloc - sonar localization and map-making daemon.
#
#   make            build the product into build/: the daemon, its clients and tools, the
#                   libraries and the bindings (BINS)
#   make test       install missing packages, build the product and its unit tests, run
#                   the product's tests (unit tests under AddressSanitizer +
#                   UndefinedBehaviorSanitizer, then the integration tests and the
#                   goldens); nothing of the laboratory is built
#   make demo       houghlocd drives the built-in simulated robot through the lab
#                   (WORLD=corridor: the second building)
#   make lab        build the laboratory's programs (LAB_BINS, tools/lab/lab.mk); its
#                   targets build what they need and run it: bench, logs, experiments,
#                   experiments-seeds, kidnap, eval-real, trials
#   make lab-test   the laboratory's own tests (tools/lab/tests): its programs, make
#                   kidnap and make eval-real on small inputs; CI runs it after make test
#   make fuzz       the fuzz targets under libFuzzer (tests/fuzz/fuzz.mk)
#   make crash-trials  kill -9 of houghlocd during a replay, 100 times (src/daemon)
#   make clean
#
# The product's fragments (src/*/*.mk, tools/*/*.mk, tests/*/*.mk, packaging/*.mk) add
# their programs to BINS and their tests to TEST_BINS and INTEGRATION_TESTS; the lab's
# (tools/lab/lab.mk and tools/lab/*/*.mk) add theirs to LAB_BINS, LAB_TEST_BINS and
# LAB_INTEGRATION_TESTS.

BUILD    ?= build
CC       ?= cc
CXX      ?= c++
V        ?= 0
Q        := $(if $(filter 1,$(V)),,@)

PKGS_C   := lcm
PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS_C) 2>/dev/null)
PKG_LIBS   := $(shell pkg-config --libs $(PKGS_C) 2>/dev/null)
CMOCKA_LIBS := $(shell pkg-config --libs cmocka 2>/dev/null)
EIGEN_CFLAGS := $(shell pkg-config --cflags eigen3 2>/dev/null)
CAIRO_CFLAGS := $(shell pkg-config --cflags cairo 2>/dev/null)
CAIRO_LIBS   := $(shell pkg-config --libs cairo 2>/dev/null)

WARN     := -Wall -Wextra -Werror -Wshadow -Wpointer-arith -Wformat=2
CWARN    := $(WARN) -Wmissing-prototypes -Wstrict-prototypes
OPT      ?= -O2 -g
SAN      := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
# Layers are enforced here: each compiles with the public headers of its own layer and of
# those it builds on, and nothing else. include/core/houghloc is the core's API (and
# libhoughloc's installed headers); include/robot, include/bus and include/store those of
# the robot link, the bus and the map and key files. include/internal holds what is not
# API, one folder per layer that implements it, each spelt houghloc-internal/NAME.h:
# include/internal/core the core's private modules (the pose graph, loop closure's
# matcher, the solve layer's interface) that the core's and the solve layer's tests and
# the laboratory's research tools read. Only src/bus and the tools see the generated LCM
# headers (LCMGEN_CPPFLAGS); only src/daemon sees its own folder.
HL_DEFS      := -D_POSIX_C_SOURCE=200809L -MMD -MP
CORE_INC     := -Iinclude/core
CORE_INTERNAL_INC   := -Iinclude/internal/core
PUBLIC_INC   := $(CORE_INC) -Iinclude/robot -Iinclude/bus -Iinclude/store
CORE_CPPFLAGS  := $(CORE_INC) $(CORE_INTERNAL_INC) $(HL_DEFS)
ROBOT_CPPFLAGS := $(CORE_INC) -Iinclude/robot $(HL_DEFS)
LCMGEN_CPPFLAGS := -I$(BUILD)/lcmtypes
BUS_CPPFLAGS   := $(CORE_INC) -Iinclude/bus $(LCMGEN_CPPFLAGS) $(HL_DEFS)
STORE_CPPFLAGS := $(CORE_INC) -Iinclude/bus -Iinclude/store $(HL_DEFS)
# Tools (and the tests' generic rule): every layer's public headers; the lab's research
# tools and the core's tests add the internal ones (their rules below and in lab.mk).
TOOL_CPPFLAGS  := $(PUBLIC_INC) $(HL_DEFS)
CPPFLAGS := $(TOOL_CPPFLAGS) $(LCMGEN_CPPFLAGS)
CFLAGS   := -std=c11 $(CWARN) $(OPT)
CXXFLAGS := -std=c++17 $(WARN) $(OPT) $(EIGEN_CFLAGS)
# What every program linking the core needs besides: the math library, and the C++
# runtime of the solve layer (src/solve: the pose-graph fit's sparse Cholesky on Eigen,
# which the core's library carries and calls through the C interface of solve.h).
SYS_LIBS := -lstdc++ -lm

# ---- core library (pure C11, no I/O) -------------------------------------------------
# The core and its solve layer are compiled with hidden visibility: a symbol leaves
# libhoughloc.so only when its declaration carries HL_API (houghloc/export.h), so the
# shared library's ABI is the public headers' functions and nothing of the internal
# modules (closure, posegraph, judge, ...). tests/integration/test_install.sh checks it.
HIDDEN    := -fvisibility=hidden
CORE_SRCS := $(sort $(wildcard src/core/*.c))
TRIG_SRC  := $(BUILD)/gen/trig_table.c

# The blur, peak and vote kernels are plain loops over contiguous runs, written to be
# vectorized; GCC's -O2 cost model would leave them scalar.
VECTOR_FLAGS := -ftree-vectorize -fvect-cost-model=dynamic
KERNEL_SRCS  := src/core/blur.c src/core/peak.c src/core/localize.c src/core/votelone.c

# ---- LCM types, generated at build time (never committed) -----------------------------
LCM_DEFS   := $(wildcard lcmtypes/*.lcm)
LCM_NAMES  := $(patsubst lcmtypes/houghloc_%.lcm,%,$(LCM_DEFS))
LCM_C_SRCS := $(patsubst %,$(BUILD)/lcmtypes/houghloc_%.c,$(LCM_NAMES))
LCM_STAMP  := $(BUILD)/lcmtypes/.stamp

obj     = $(patsubst %.c,$(BUILD)/obj/%.o,$(patsubst %.cpp,$(BUILD)/obj/%.o,$(1)))
asanobj = $(patsubst %.c,$(BUILD)/asan/%.o,$(1))

# The core's library carries the solve layer (src/solve/solve.mk): C++ on Eigen, compiled
# with Eigen's include path alone, called by the core through houghloc-internal/solve.h
# (include/internal/core).
SOLVE_SRCS := $(sort $(wildcard src/solve/*.cpp))
CORE_OBJS      := $(call obj,$(CORE_SRCS) $(SOLVE_SRCS)) $(BUILD)/obj/gen/trig_table.o
CORE_ASAN_OBJS := $(call asanobj,$(CORE_SRCS)) $(patsubst %.cpp,$(BUILD)/asan/%.o,$(SOLVE_SRCS)) \
                  $(BUILD)/asan/gen/trig_table.o
LCM_OBJS       := $(call obj,$(LCM_C_SRCS:$(BUILD)/%=%))
LCM_ASAN_OBJS  := $(call asanobj,$(LCM_C_SRCS:$(BUILD)/%=%))

CORE_LIB      := $(BUILD)/lib/libhoughloc_core.a
CORE_ASAN_LIB := $(BUILD)/lib/libhoughloc_core_asan.a
LCM_LIB       := $(BUILD)/lib/libhoughloc_lcmtypes.a

# ---- unit tests (cmocka, under ASan + UBSan) ------------------------------------------
CORE_TESTS := $(patsubst tests/core/%.c,$(BUILD)/tests/core/%,$(wildcard tests/core/test_*.c))
TEST_BINS  := $(CORE_TESTS)
BINS       :=
LAB_BINS   :=
# Every product program's usage (test_usage.sh) and the layering the include paths
# cannot enforce (test_layers.sh).
INTEGRATION_TESTS := tests/integration/test_usage.sh tests/integration/test_layers.sh

.PHONY: all deps test unit-test demo clean lcmtypes
.DEFAULT_GOAL := all

# The layers in their order, each seeing the libraries of those before it: src/bus/bus.mk
# the bus library, src/robot/robot.mk the robot link's, src/store/store.mk the map and key
# files', src/daemon/daemon.mk houghlocd,
# src/solve/solve.mk the sparse solver on Eigen (C++, Eigen's include path its own); then tools/*/*.mk the separate programs and packaging/packaging.mk `make install`;
# last the laboratory, tools/lab/lab.mk, which builds on all of them.
include src/bus/bus.mk src/robot/robot.mk src/store/store.mk src/daemon/daemon.mk
include src/solve/solve.mk
-include $(sort $(filter-out tools/lab/%,$(wildcard tools/*/*.mk tests/*/*.mk packaging/*.mk)))
include tools/lab/lab.mk

# The sanitized bus library carries a sanitized copy of the generated code, so every test
# that links it (bus, daemon) takes the generated functions from there, not $(LCM_LIB).
$(BUS_ASAN_LIB): $(LCM_ASAN_OBJS)

all: $(BINS)

deps:
	$(Q)sh tools/build/install-deps.sh

# ---- generated sources ----------------------------------------------------------------
$(BUILD)/bin/gen_trig_table: tools/build/gen_trig_table.c
	@mkdir -p $(@D)
	$(Q)$(CC) -std=c11 -O1 -o $@ $< $(SYS_LIBS)

$(TRIG_SRC): $(BUILD)/bin/gen_trig_table
	@mkdir -p $(@D)
	$(Q)$< > $@.tmp && mv $@.tmp $@

# lcm-gen fails unless the output folder exists.
$(LCM_STAMP): $(LCM_DEFS)
	@mkdir -p $(BUILD)/lcmtypes
	$(Q)lcm-gen -c --c-cpath $(BUILD)/lcmtypes --c-hpath $(BUILD)/lcmtypes $(LCM_DEFS)
	$(Q)lcm-gen -x --cpp-hpath $(BUILD)/lcmtypes $(LCM_DEFS)
	$(Q)touch $@
$(LCM_C_SRCS): $(LCM_STAMP)
lcmtypes: $(LCM_STAMP)

# ---- compile rules --------------------------------------------------------------------
$(BUILD)/obj/gen/%.o: $(BUILD)/gen/%.c
	@mkdir -p $(@D)
	$(Q)$(CC) $(CORE_CPPFLAGS) $(CFLAGS) $(HIDDEN) -c -o $@ $<
$(BUILD)/asan/gen/%.o: $(BUILD)/gen/%.c
	@mkdir -p $(@D)
	$(Q)$(CC) $(CORE_CPPFLAGS) $(CFLAGS) $(HIDDEN) $(SAN) -c -o $@ $<
# Generated LCM code is not ours to fix: compile it without -Werror extras.
$(BUILD)/obj/lcmtypes/%.o: $(BUILD)/lcmtypes/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	$(Q)$(CC) $(CPPFLAGS) -std=c11 $(OPT) -c -o $@ $<
# ... but the tests run it under the sanitizers too, so UBSan sees inside it (lcm_coretypes.h's
# memcpy of an array of zero elements, for one).
$(BUILD)/asan/lcmtypes/%.o: $(BUILD)/lcmtypes/%.c $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(CPPFLAGS) -std=c11 $(OPT) $(SAN) -c -o $@ $<
$(BUILD)/obj/%.o: %.c | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CC      $<"
	$(Q)$(CC) $(CPPFLAGS) $(PKG_CFLAGS) $(CAIRO_CFLAGS) $(CFLAGS) -c -o $@ $<
$(BUILD)/obj/%.o: %.cpp | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CXX     $<"
	$(Q)$(CXX) $(CPPFLAGS) $(PKG_CFLAGS) $(CAIRO_CFLAGS) $(CXXFLAGS) -c -o $@ $<
# The core: its own include paths and nothing else (no LCM, glib, Eigen or cairo).
$(BUILD)/obj/src/core/%.o: src/core/%.c
	@mkdir -p $(@D)
	@echo "  CC      $<"
	$(Q)$(CC) $(CORE_CPPFLAGS) $(CFLAGS) $(HIDDEN) -c -o $@ $<
$(BUILD)/asan/src/core/%.o: src/core/%.c
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(CORE_CPPFLAGS) $(CFLAGS) $(HIDDEN) $(SAN) -c -o $@ $<
# The core's tests also read its private modules: houghloc-internal/ and src/core's own
# headers (peak.h, blur.h); and the tests' support (tests/support: synthetic rooms, the
# reference localizer).
$(BUILD)/asan/tests/core/%.o: CPPFLAGS += $(CORE_INTERNAL_INC) -Isrc/core $(TEST_SUPPORT_INC)
$(BUILD)/asan/%.o: %.c | $(LCM_STAMP)
	@mkdir -p $(@D)
	@echo "  CC-SAN  $<"
	$(Q)$(CC) $(CPPFLAGS) $(PKG_CFLAGS) $(CFLAGS) $(SAN) -c -o $@ $<

$(patsubst %.c,$(BUILD)/obj/%.o,$(KERNEL_SRCS)): CFLAGS += $(VECTOR_FLAGS)

$(BUILD)/lib/%.a:
	@mkdir -p $(@D)
	$(Q)rm -f $@ && ar rcs $@ $^
$(CORE_LIB): $(CORE_OBJS)
$(CORE_ASAN_LIB): $(CORE_ASAN_OBJS)
$(LCM_LIB): $(LCM_OBJS)

# ---- unit tests -----------------------------------------------------------------------
$(BUILD)/tests/core/%: $(BUILD)/asan/tests/core/%.o $(TEST_SUPPORT_ASAN_LIB) $(CORE_ASAN_LIB)
	@mkdir -p $(@D)
	@echo "  LD-SAN  $@"
	$(Q)$(CC) $(SAN) -o $@ $^ $(TEST_LDFLAGS) $(CMOCKA_LIBS) $(SYS_LIBS)

unit-test: $(TEST_BINS)
	$(Q)sh tests/run-unit.sh $(TEST_BINS)

# The product's tests: they run the programs `make` builds, nothing of the laboratory
# (its tests are make lab-test's, tools/lab/lab.mk).
test: deps
	$(Q)$(MAKE) --no-print-directory all
	$(Q)$(MAKE) --no-print-directory unit-test
	$(Q)sh tests/run-integration.sh $(INTEGRATION_TESTS)

# The product on the built-in simulated robot: houghlocd drives houghloc-sim through a
# scripted tour of WORLD (lab or corridor) with houghloc-goto; hl-eval scores the log
# against the simulator's ground truth (tools/demo/demo.sh).
WORLD ?= lab
demo: deps
	$(Q)$(MAKE) --no-print-directory $(BUILD)/bin/houghlocd $(BUILD)/bin/houghloc-sim \
	    $(BUILD)/bin/houghloc-goto $(BUILD)/bin/hl-eval $(BUILD)/bin/houghloc-map \
	    $(BUILD)/bin/houghloc-console
	$(Q)BUILD=$(BUILD) WORLD=$(WORLD) sh tools/demo/demo.sh

clean:
	rm -rf $(BUILD)

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
