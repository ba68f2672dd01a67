# packaging/lib.mk - the core as a library, for programs that embed the localizer:
#
#   $(BUILD)/lib/libhoughloc.a                  the core's objects, as CORE_OBJS
#   $(BUILD)/lib/libhoughloc.so.$(HL_LIB_VERSION)  the same sources compiled once more
#                                               with -fPIC into $(BUILD)/pic/
#   make install-lib / uninstall-lib            the libraries, the public headers and
#                                               houghloc.pc (also part of make install)
#
# Installed layout (under $(DESTDIR)):
#   $(LIBDIR)/libhoughloc.a                               0644
#   $(LIBDIR)/libhoughloc.so.X.Y.Z                        0644, soname libhoughloc.so.X
#   $(LIBDIR)/libhoughloc.so.X -> libhoughloc.so.X.Y.Z    the name the loader looks for
#   $(LIBDIR)/libhoughloc.so -> libhoughloc.so.X          the name the linker looks for
#   $(INCLUDEDIR)/houghloc/*.h                            the core's public headers, 0644
#   $(LIBDIR)/pkgconfig/houghloc.pc                       from houghloc.pc.in, 0644
# LIBDIR is $(PREFIX)/lib, except for PREFIX=/usr: the multiarch folder
# (/usr/lib/x86_64-linux-gnu), where Debian puts its libraries. pkg-config and the
# loader search both by default (/usr/local/lib through the loader's cache: install runs
# ldconfig when it installs as root into the real system); set LIBDIR to override.
#
# The version comes from include/core/houghloc/version.h (HL_VERSION), so the library, its
# .pc file and every program's --version say the same. The soname carries the major
# number only.

HL_LIB_VERSION := $(shell sed -n 's/^\#define HL_VERSION "\([0-9][0-9.]*\)"$$/\1/p' include/core/houghloc/version.h)
HL_LIB_MAJOR   := $(firstword $(subst ., ,$(HL_LIB_VERSION)))
HL_LIB_SONAME  := libhoughloc.so.$(HL_LIB_MAJOR)
HL_LIB_A       := $(BUILD)/lib/libhoughloc.a
HL_LIB_SO      := $(BUILD)/lib/libhoughloc.so.$(HL_LIB_VERSION)

# The headers a caller of the core needs: the core's public folder, include/core/houghloc
# (none of the robot link's, the bus's or the store's: those need libserialport, LCM,
# libsodium, zlib). tests/integration/test_install.sh compiles each alone against the
# installed folder.
HL_PUBLIC_HEADERS := $(sort $(wildcard include/core/houghloc/*.h))

MULTIARCH  := $(shell $(CC) -print-multiarch 2>/dev/null)
LIBDIR     ?= $(if $(and $(filter /usr /usr/,$(PREFIX)),$(MULTIARCH)),/usr/lib/$(MULTIARCH),$(PREFIX)/lib)
INCLUDEDIR ?= $(PREFIX)/include
PCDIR      ?= $(LIBDIR)/pkgconfig

# The same objects as CORE_OBJS (same flags, the vectorized kernels included), position
# independent: a shared library cannot be made from the PIE objects of the programs.
CORE_PIC_OBJS := $(patsubst $(BUILD)/obj/%,$(BUILD)/pic/%,$(CORE_OBJS))

$(BUILD)/pic/src/core/%.o: src/core/%.c
	@mkdir -p $(@D)
	@echo "  CC-PIC  $<"
	$(Q)$(CC) $(CORE_CPPFLAGS) $(CFLAGS) $(HIDDEN) -fPIC -c -o $@ $<
$(BUILD)/pic/gen/%.o: $(BUILD)/gen/%.c
	@mkdir -p $(@D)
	@echo "  CC-PIC  $<"
	$(Q)$(CC) $(CORE_CPPFLAGS) $(CFLAGS) $(HIDDEN) -fPIC -c -o $@ $<
$(BUILD)/pic/src/solve/%.o: src/solve/%.cpp
	@mkdir -p $(@D)
	@echo "  CXX-PIC $<"
	$(Q)$(CXX) $(CORE_CPPFLAGS) $(CXXFLAGS) $(HIDDEN) -fPIC -c -o $@ $<
$(patsubst %.c,$(BUILD)/pic/%.o,$(KERNEL_SRCS)): CFLAGS += $(VECTOR_FLAGS)

# The static library: the programs' own core objects (the generic $(BUILD)/lib/%.a rule).
$(HL_LIB_A): $(CORE_OBJS)

# The shared library exports the public API only: the core is compiled with hidden
# visibility and its public headers mark their functions HL_API (houghloc/export.h), so
# the core's internal modules (closure, posegraph, judge, ...) stay out of the ABI.
# packaging/libhoughloc.map keeps in what the C++ standard library instantiates in the
# solve layer. -z defs refuses a library with an unresolved symbol.
$(HL_LIB_SO): $(CORE_PIC_OBJS) packaging/libhoughloc.map
	@mkdir -p $(@D)
	@echo "  LD-SO   $@"
	$(Q)$(CC) -shared -Wl,-soname,$(HL_LIB_SONAME) -Wl,--version-script=packaging/libhoughloc.map \
	    -Wl,-z,defs $(LDFLAGS) -o $@ $(CORE_PIC_OBJS) $(SYS_LIBS)

.PHONY: lib install-lib uninstall-lib
lib: $(HL_LIB_A) $(HL_LIB_SO)
all: lib

# The .pc file is made here, not at build time, so that it names the PREFIX and LIBDIR
# given to install. Paths under the prefix are written as ${prefix}/..., so that
# pkg-config --define-prefix can move them.
HL_PC_LIBDIR     = $(patsubst $(PREFIX)/%,$${prefix}/%,$(LIBDIR))
HL_PC_INCLUDEDIR = $(patsubst $(PREFIX)/%,$${prefix}/%,$(INCLUDEDIR))

install-lib: $(HL_LIB_A) $(HL_LIB_SO) packaging/houghloc.pc.in
	install -d -m 0755 $(DESTDIR)$(LIBDIR) $(DESTDIR)$(PCDIR) $(DESTDIR)$(INCLUDEDIR)/houghloc
	install -m 0644 $(HL_LIB_A) $(HL_LIB_SO) $(DESTDIR)$(LIBDIR)/
	ln -sf libhoughloc.so.$(HL_LIB_VERSION) $(DESTDIR)$(LIBDIR)/$(HL_LIB_SONAME)
	ln -sf $(HL_LIB_SONAME) $(DESTDIR)$(LIBDIR)/libhoughloc.so
	install -m 0644 $(HL_PUBLIC_HEADERS) $(DESTDIR)$(INCLUDEDIR)/houghloc/
	sed -e '/^#/d' -e 's|@PREFIX@|$(PREFIX)|g' -e 's|@LIBDIR@|$(HL_PC_LIBDIR)|g' \
	    -e 's|@INCLUDEDIR@|$(HL_PC_INCLUDEDIR)|g' -e 's|@VERSION@|$(HL_LIB_VERSION)|g' \
	    packaging/houghloc.pc.in | install -m 0644 /dev/stdin $(DESTDIR)$(PCDIR)/houghloc.pc
	@# The loader finds a new library in /usr/local/lib only through its cache: refresh
	@# it on a real install as root, never into a staging folder.
	@if [ -z "$(DESTDIR)" ] && [ "$$(id -u)" = 0 ] && command -v ldconfig >/dev/null; then \
	    echo ldconfig; ldconfig; fi

uninstall-lib:
	rm -f $(addprefix $(DESTDIR)$(LIBDIR)/,libhoughloc.a libhoughloc.so.$(HL_LIB_VERSION) \
	    $(HL_LIB_SONAME) libhoughloc.so)
	rm -f $(DESTDIR)$(PCDIR)/houghloc.pc
	rm -f $(addprefix $(DESTDIR)$(INCLUDEDIR)/houghloc/,$(notdir $(HL_PUBLIC_HEADERS)))
	@rmdir $(DESTDIR)$(INCLUDEDIR)/houghloc 2>/dev/null || true
	@if [ -z "$(DESTDIR)" ] && [ "$$(id -u)" = 0 ] && command -v ldconfig >/dev/null; then \
	    echo ldconfig; ldconfig; fi
