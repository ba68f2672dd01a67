# packaging/packaging.mk - `make install`, `make uninstall` and `make bindings`.
#
#   make install   [PREFIX=/usr/local] [DESTDIR=]     (docs/service.md)
#   make uninstall [PREFIX=/usr/local] [DESTDIR=]
#   make bindings  the LCM types for Python and, when a JDK and liblcm-java are present,
#                  the jar that lets lcm-spy decode houghloc's channels
#
# Layout (every path under $(DESTDIR)):
#   $(BINDIR)/houghlocd, houghloc-goto, houghloc-ctl,      programs, 0755
#     houghloc-map, houghloc-import-carmen, houghloc-eval
#   $(UNITDIR)/houghlocd.service                           0644, from houghlocd.service.in
#   $(SYSCONFDIR)/houghloc/houghlocd.conf                  0644, never overwritten: a
#                                                          changed one gets .dist beside it
#   $(DATADIR)/python/houghloc/*.py                        the Python types, 0644
#   $(DATADIR)/java/houghloc_lcmtypes.jar                  the Java types, 0644
# The unit goes to /lib/systemd/system when PREFIX=/usr (where Debian's own packages put
# units) and to $(PREFIX)/lib/systemd/system otherwise (systemd also reads
# /usr/local/lib/systemd/system). Nothing here needs root: no useradd (the unit uses
# DynamicUser=), no systemctl (enabling is the administrator's step), no chown.
# This file is read before the other fragments (the include list is sorted), so rules
# name the programs by path rather than through BINS.

PREFIX     ?= /usr/local
DESTDIR    ?=
BINDIR     ?= $(PREFIX)/bin
SYSCONFDIR ?= /etc
DATADIR    ?= $(PREFIX)/share/houghloc
UNITDIR    ?= $(if $(filter /usr /usr/,$(PREFIX)),/lib/systemd/system,$(PREFIX)/lib/systemd/system)

INSTALL_NAMES := houghlocd houghloc-goto houghloc-ctl houghloc-map houghloc-import-carmen \
                 houghloc-eval
INSTALL_PROGS := $(addprefix $(BUILD)/bin/,$(INSTALL_NAMES))
UNIT_IN       := packaging/houghlocd.service.in
CONF_SRC      := packaging/houghlocd.conf

# ---- LCM bindings -----------------------------------------------------------------------
PY_DIR    := $(BUILD)/python
PY_STAMP  := $(PY_DIR)/.stamp
JAVA_DIR  := $(BUILD)/java
JAVA_JAR  := $(JAVA_DIR)/houghloc_lcmtypes.jar
LCM_JAR   ?= /usr/share/java/lcm.jar
JAVAC     := $(shell command -v javac 2>/dev/null)
JARTOOL   := $(shell command -v jar 2>/dev/null)
HAVE_JAVA := $(if $(and $(JAVAC),$(JARTOOL),$(wildcard $(LCM_JAR))),yes)
JAVA_SKIP_MSG := houghloc: skipping the Java types for lcm-spy: install liblcm-java and a JDK (sudo apt-get install liblcm-java default-jdk-headless)

# Python: only the standard library's struct is needed to encode and decode; the `lcm`
# module (PyPI) only to publish and subscribe. lcm-gen leaves types that are gone, so
# start from an empty folder. lcm-gen 1.3.1 decodes a boolean array with Python 2's
# map(), which Python 3 makes a one-shot iterator (scan_t.valid could be read once and
# the message no longer encodes): the sed makes it a list, as later LCM releases do.
$(PY_STAMP): $(LCM_DEFS) packaging/packaging.mk
	@rm -rf $(PY_DIR)/houghloc
	@mkdir -p $(PY_DIR)
	@echo "  LCMGEN  $(PY_DIR)/houghloc"
	$(Q)lcm-gen -p --ppath $(PY_DIR) $(LCM_DEFS)
	$(Q)sed -i 's/ = map(bool, \(.*\))$$/ = list(map(bool, \1))/' $(PY_DIR)/houghloc/*.py
	$(Q)touch $@

# Java: compiled for Java 8, the level of Debian's lcm.jar, so any JRE that runs lcm-spy
# loads it.
$(JAVA_JAR): $(LCM_DEFS)
	@rm -rf $(JAVA_DIR)
	@mkdir -p $(JAVA_DIR)/src $(JAVA_DIR)/classes
	@echo "  JAR     $@"
	$(Q)lcm-gen -j --jpath $(JAVA_DIR)/src $(LCM_DEFS)
	$(Q)$(JAVAC) --release 8 -Xlint:-options -cp $(LCM_JAR) -d $(JAVA_DIR)/classes \
	    $$(find $(JAVA_DIR)/src -name '*.java' | sort)
	$(Q)$(JARTOOL) cf $@.tmp -C $(JAVA_DIR)/classes . && mv $@.tmp $@

# The C side of tests/integration/test_bindings.sh.
$(BUILD)/bin/hl-pose-bytes: $(call obj,tools/bindings/pose_bytes.c) $(LCM_LIB)
	@mkdir -p $(@D)
	@echo "  LD      $@"
	$(Q)$(CC) -o $@ $^ $(PKG_LIBS)

.PHONY: bindings install uninstall
BINS += $(BUILD)/bin/hl-pose-bytes
INTEGRATION_TESTS += tests/integration/test_bindings.sh tests/integration/test_packaging.sh
# `make` builds the bindings too (so that the tests find them), the jar only when it can.
all: $(PY_STAMP) $(if $(HAVE_JAVA),$(JAVA_JAR))

bindings: $(PY_STAMP) $(if $(HAVE_JAVA),$(JAVA_JAR))
	$(if $(HAVE_JAVA),,@echo "$(JAVA_SKIP_MSG)")

# ---- install / uninstall ------------------------------------------------------------------
install: $(INSTALL_PROGS) $(UNIT_IN) $(CONF_SRC) bindings
	install -d -m 0755 $(DESTDIR)$(BINDIR) $(DESTDIR)$(UNITDIR) \
	    $(DESTDIR)$(SYSCONFDIR)/houghloc $(DESTDIR)$(DATADIR)/python/houghloc
	install -m 0755 $(INSTALL_PROGS) $(DESTDIR)$(BINDIR)/
	@# The unit is made here, not at build time, so that it names the PREFIX given to
	@# install; it goes straight to DESTDIR, so an install writes nothing in $(BUILD).
	sed -e 's|@BINDIR@|$(BINDIR)|g' -e 's|@SYSCONFDIR@|$(SYSCONFDIR)|g' $(UNIT_IN) | \
	    install -m 0644 /dev/stdin $(DESTDIR)$(UNITDIR)/houghlocd.service
	@# The administrator's configuration is theirs: a changed one stays, and the new
	@# default lands beside it as houghlocd.conf.dist to compare with.
	@conf=$(DESTDIR)$(SYSCONFDIR)/houghloc/houghlocd.conf; \
	if [ -e "$$conf" ] && ! cmp -s $(CONF_SRC) "$$conf"; then \
	    echo "install -m 0644 $(CONF_SRC) $$conf.dist   (keeping the changed $$conf)"; \
	    install -m 0644 $(CONF_SRC) "$$conf.dist"; \
	else \
	    echo "install -m 0644 $(CONF_SRC) $$conf"; \
	    install -m 0644 $(CONF_SRC) "$$conf"; \
	fi
	install -m 0644 $(PY_DIR)/houghloc/*.py $(DESTDIR)$(DATADIR)/python/houghloc/
	$(if $(HAVE_JAVA),install -d -m 0755 $(DESTDIR)$(DATADIR)/java)
	$(if $(HAVE_JAVA),install -m 0644 $(JAVA_JAR) $(DESTDIR)$(DATADIR)/java/)

# Removes what install added. The configuration goes only if it is still the shipped one;
# the key (/etc/houghloc/key) and the state directory (the map) are never touched.
uninstall:
	rm -f $(addprefix $(DESTDIR)$(BINDIR)/,$(INSTALL_NAMES))
	rm -f $(DESTDIR)$(UNITDIR)/houghlocd.service
	rm -rf $(DESTDIR)$(DATADIR)/python/houghloc
	rm -f $(DESTDIR)$(DATADIR)/java/houghloc_lcmtypes.jar
	@rmdir $(DESTDIR)$(DATADIR)/python $(DESTDIR)$(DATADIR)/java 2>/dev/null || true
	@rmdir $(DESTDIR)$(DATADIR) 2>/dev/null || true
	rm -f $(DESTDIR)$(SYSCONFDIR)/houghloc/houghlocd.conf.dist
	@conf=$(DESTDIR)$(SYSCONFDIR)/houghloc/houghlocd.conf; \
	if [ -e "$$conf" ] && ! cmp -s $(CONF_SRC) "$$conf"; then \
	    echo "keeping the changed $$conf"; \
	else \
	    echo "rm -f $$conf"; rm -f "$$conf"; \
	    rmdir $(DESTDIR)$(SYSCONFDIR)/houghloc 2>/dev/null || true; \
	fi
