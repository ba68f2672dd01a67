# packaging/packaging.mk - `make install`, `make uninstall` and `make bindings`.
#
#   make install   [PREFIX=/usr/local] [DESTDIR=]     (docs/manual/service.md)
#   make uninstall [PREFIX=/usr/local] [DESTDIR=]
#   make bindings  the LCM types for Python and, when a JDK and liblcm-java are present,
#                  the jar that lets lcm-spy decode houghloc's channels
#
# Layout (every path under $(DESTDIR)):
#   $(BINDIR)/houghlocd, houghloc-goto, houghloc-ctl,      programs, 0755
#     houghloc-console, houghloc-sim, houghloc-map,
#     houghloc-import-carmen, houghloc-eval
#   $(MANDIR)/man1, man5, man8/*.gz                        man/*.[158], gzip -9n, 0644
#   $(UNITDIR)/houghlocd.service                           0644, from houghlocd.service.in
#   $(SYSCONFDIR)/houghloc/houghlocd.conf                  0644, never overwritten: a
#                                                          changed one gets .dist beside it
#   $(DATADIR)/lcmtypes/*.lcm                              the LCM type definitions, 0644
#   $(DATADIR)/profiles/NAME.conf                          each sensor profile's keys, as
#                                                          `houghlocd --print-profile NAME`
#                                                          prints them, 0644
#   $(PYTHONDIR)/houghloc/*.py                             the Python types, 0644
#   $(DATADIR)/java/houghloc_lcmtypes.jar                  the Java types, 0644
#   $(DOCDIR)/README.md, LICENSE, CHANGELOG.md,            the documentation, 0644
#     manual/, design/, results/ (*.md, results/img/*.png)
#   the core as a library (libhoughloc.a/.so, headers, houghloc.pc): packaging/lib.mk
# The unit goes to /lib/systemd/system when PREFIX=/usr (where Debian's own packages put
# units) and to $(PREFIX)/lib/systemd/system otherwise (systemd also reads
# /usr/local/lib/systemd/system). The Python types go where Debian's python3 looks:
# /usr/lib/python3/dist-packages for PREFIX=/usr, /usr/local/lib/python3.X/dist-packages
# for /usr/local; for another PREFIX, $(PREFIX)/lib/python3.X/site-packages, which is
# Python's own user folder for PREFIX=~/.local and otherwise wants PYTHONPATH.
# Nothing here needs root: no useradd (the unit uses DynamicUser=), no systemctl
# (enabling is the administrator's step), no chown. Everything install copies is built
# by `make` (or made straight into $(DESTDIR)), so an install writes nothing in $(BUILD).
# This file is read before the programs' fragments (the include list is sorted), so
# rules name the programs by path rather than through BINS.

PREFIX     ?= /usr/local
DESTDIR    ?=
BINDIR     ?= $(PREFIX)/bin
SYSCONFDIR ?= /etc
DATADIR    ?= $(PREFIX)/share/houghloc
UNITDIR    ?= $(if $(filter /usr /usr/,$(PREFIX)),/lib/systemd/system,$(PREFIX)/lib/systemd/system)
MANDIR     ?= $(PREFIX)/share/man
DOCDIR     ?= $(PREFIX)/share/doc/houghloc
# Debian's python3, not one first on PATH (a pyenv's would not read dist-packages).
PYTHON     ?= $(firstword $(wildcard /usr/bin/python3) python3)
PYTHON_VERSION = $(shell $(PYTHON) -c 'import sys; print("%d.%d" % sys.version_info[:2])')
PYTHONDIR  ?= $(if $(filter /usr /usr/,$(PREFIX)),/usr/lib/python3/dist-packages,$(PREFIX)/lib/python$(PYTHON_VERSION)/$(if $(filter /usr/local /usr/local/,$(PREFIX)),dist,site)-packages)

INSTALL_NAMES := houghlocd houghloc-goto houghloc-ctl houghloc-console houghloc-sim \
                 houghloc-map houghloc-import-carmen houghloc-eval
INSTALL_PROGS := $(addprefix $(BUILD)/bin/,$(INSTALL_NAMES))
UNIT_IN       := packaging/houghlocd.service.in
CONF_SRC      := packaging/houghlocd.conf
MAN_PAGES     := $(sort $(wildcard man/*.[158]))
SENSOR_PROFILES := sonar-stops sonar-continuous laser paper

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
INTEGRATION_TESTS += tests/integration/test_bindings.sh tests/integration/test_packaging.sh \
                     tests/integration/test_install.sh tests/integration/test_manpages.sh
# `make` builds the bindings too (so that the tests find them), the jar only when it can.
all: $(PY_STAMP) $(if $(HAVE_JAVA),$(JAVA_JAR))

bindings: $(PY_STAMP) $(if $(HAVE_JAVA),$(JAVA_JAR))
	$(if $(HAVE_JAVA),,@echo "$(JAVA_SKIP_MSG)")

# ---- install / uninstall ------------------------------------------------------------------
# The documentation: the front page and the three folders of docs/ (one level each).
DOC_TOP   := README.md LICENSE CHANGELOG.md
DOC_FILES := $(sort $(wildcard docs/manual/*.md docs/design/*.md docs/results/*.md docs/results/img/*.png))

install: $(INSTALL_PROGS) $(UNIT_IN) $(CONF_SRC) $(MAN_PAGES) bindings install-lib
	install -d -m 0755 $(DESTDIR)$(BINDIR) $(DESTDIR)$(UNITDIR) \
	    $(DESTDIR)$(SYSCONFDIR)/houghloc $(DESTDIR)$(DATADIR)/lcmtypes \
	    $(DESTDIR)$(DATADIR)/profiles $(DESTDIR)$(PYTHONDIR)/houghloc \
	    $(addprefix $(DESTDIR)$(MANDIR)/man,$(sort $(subst .,,$(suffix $(MAN_PAGES)))))
	install -m 0755 $(INSTALL_PROGS) $(DESTDIR)$(BINDIR)/
	@# Man pages compressed as Debian ships them: -n leaves out the name and time, so
	@# the same page gives the same bytes.
	@for page in $(MAN_PAGES); do \
	    dest=$(DESTDIR)$(MANDIR)/man$${page##*.}/$${page##*/}.gz; \
	    echo "gzip -9n < $$page > $$dest"; \
	    gzip -9n <"$$page" | install -m 0644 /dev/stdin "$$dest" || exit 1; \
	done
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
	install -m 0644 $(LCM_DEFS) $(DESTDIR)$(DATADIR)/lcmtypes/
	@# The profiles are what the installed daemon itself applies: printed by it, not
	@# copied from a file that could drift from the compiled-in presets.
	@for name in $(SENSOR_PROFILES); do \
	    dest=$(DESTDIR)$(DATADIR)/profiles/$$name.conf; \
	    echo "houghlocd --print-profile $$name > $$dest"; \
	    $(BUILD)/bin/houghlocd --print-profile $$name >"$$dest.tmp" && \
	    install -m 0644 "$$dest.tmp" "$$dest" && rm -f "$$dest.tmp" || \
	    { rm -f "$$dest.tmp"; echo "houghloc: houghlocd --print-profile $$name failed" >&2; exit 1; }; \
	done
	install -m 0644 $(PY_DIR)/houghloc/*.py $(DESTDIR)$(PYTHONDIR)/houghloc/
	$(if $(HAVE_JAVA),install -d -m 0755 $(DESTDIR)$(DATADIR)/java)
	$(if $(HAVE_JAVA),install -m 0644 $(JAVA_JAR) $(DESTDIR)$(DATADIR)/java/)
	install -d -m 0755 $(addprefix $(DESTDIR)$(DOCDIR)/,manual design results results/img)
	install -m 0644 $(DOC_TOP) $(DESTDIR)$(DOCDIR)/
	$(foreach d,manual design results results/img,install -m 0644 $(wildcard docs/$(d)/*.md docs/$(d)/*.png) $(DESTDIR)$(DOCDIR)/$(d)/;)

# Removes what install added. The configuration goes only if it is still the shipped one;
# the key (/etc/houghloc/key) and the state directory (the map) are never touched.
uninstall: uninstall-lib
	rm -f $(addprefix $(DESTDIR)$(DOCDIR)/,$(notdir $(DOC_TOP)) $(patsubst docs/%,%,$(DOC_FILES)))
	@rmdir $(addprefix $(DESTDIR)$(DOCDIR)/,results/img results design manual) $(DESTDIR)$(DOCDIR) 2>/dev/null || true
	rm -f $(addprefix $(DESTDIR)$(BINDIR)/,$(INSTALL_NAMES))
	rm -f $(foreach p,$(MAN_PAGES),$(DESTDIR)$(MANDIR)/man$(subst .,,$(suffix $(p)))/$(notdir $(p)).gz)
	rm -f $(DESTDIR)$(UNITDIR)/houghlocd.service
	rm -f $(addprefix $(DESTDIR)$(DATADIR)/lcmtypes/,$(notdir $(LCM_DEFS)))
	rm -f $(patsubst %,$(DESTDIR)$(DATADIR)/profiles/%.conf,$(SENSOR_PROFILES))
	rm -rf $(DESTDIR)$(PYTHONDIR)/houghloc
	rm -f $(DESTDIR)$(DATADIR)/java/houghloc_lcmtypes.jar
	@rmdir $(DESTDIR)$(DATADIR)/lcmtypes $(DESTDIR)$(DATADIR)/profiles \
	    $(DESTDIR)$(DATADIR)/java 2>/dev/null || true
	@rmdir $(DESTDIR)$(DATADIR) 2>/dev/null || true
	rm -f $(DESTDIR)$(SYSCONFDIR)/houghloc/houghlocd.conf.dist
	@conf=$(DESTDIR)$(SYSCONFDIR)/houghloc/houghlocd.conf; \
	if [ -e "$$conf" ] && ! cmp -s $(CONF_SRC) "$$conf"; then \
	    echo "keeping the changed $$conf"; \
	else \
	    echo "rm -f $$conf"; rm -f "$$conf"; \
	    rmdir $(DESTDIR)$(SYSCONFDIR)/houghloc 2>/dev/null || true; \
	fi
