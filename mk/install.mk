# SPDX-License-Identifier: BSD-2-Clause
# make install / make uninstall (host build): the command line, the shared
# library libbrdfwave.so.MAJOR with its SONAME (and the link
# libbrdfwave.so, the static library libbrdfwave.a), the public headers
# under include/brdfwave/, brdfwave.pc for pkg-config, the man pages
# brdfwave(1) and libbrdfwave(3), and the Python package.
#
#   make install PREFIX=/usr/local DESTDIR=/tmp/stage
#
# Included by mk/host.mk (VERSION, SONAME, SOLIB, LIB and BW_CLI come from there).
PREFIX ?= /usr/local
BINDIR ?= $(PREFIX)/bin
LIBDIR ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
MANDIR ?= $(PREFIX)/share/man
PKGCONFIGDIR ?= $(LIBDIR)/pkgconfig
# where Debian's python3 looks: /usr/lib/python3/dist-packages for /usr,
# PREFIX/lib/python3.X/dist-packages elsewhere (/usr/local among them)
PYTHONDIR ?= $(if $(filter /usr,$(PREFIX)),/usr/lib/python3/dist-packages,$(PREFIX)/lib/python$(PYTHON_VERSION)/dist-packages)
PYTHON_VERSION = $(shell /usr/bin/python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null)
# what the installed Python package loads: the library's path, or a name
# the dynamic loader looks up (Debian's package: libbrdfwave.so.1)
PY_LIBRARY ?= $(LIBDIR)/$(SONAME)
INSTALL ?= install

# the public headers: include/brdfwave/ and the headers of the core and the
# library those include (installed beside them, as they are), found by the
# compiler so that a header the core adds is installed with it
PUBLIC_HEADERS = $(sort $(filter %.h,$(shell $(CC) -MM $(CORE_INC) -Ifirmware/link -Ihost-tools/lib \
    -Iinclude include/brdfwave/brdfwave.h include/brdfwave/brdf.h)))
MAN_PAGES := docs/man/brdfwave.1 docs/man/libbrdfwave.3
PY_SOURCES := $(wildcard host-tools/python/brdfwave/*.py)

.PHONY: install uninstall
install: $(BW_CLI) $(SOLIB) $(LIB)
	$(INSTALL) -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(LIBDIR) $(DESTDIR)$(PKGCONFIGDIR) \
	    $(DESTDIR)$(INCLUDEDIR)/brdfwave $(DESTDIR)$(MANDIR)/man1 $(DESTDIR)$(MANDIR)/man3 \
	    $(DESTDIR)$(PYTHONDIR)/brdfwave
	$(INSTALL) -m 755 $(BW_CLI) $(DESTDIR)$(BINDIR)/brdfwave
	$(INSTALL) -m 644 $(SOLIB) $(DESTDIR)$(LIBDIR)/libbrdfwave.so.$(VERSION)
	ln -sf libbrdfwave.so.$(VERSION) $(DESTDIR)$(LIBDIR)/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libbrdfwave.so
	$(INSTALL) -m 644 $(LIB) $(DESTDIR)$(LIBDIR)/libbrdfwave.a
	$(INSTALL) -m 644 $(PUBLIC_HEADERS) $(DESTDIR)$(INCLUDEDIR)/brdfwave/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(LIBDIR)|' -e 's|@INCLUDEDIR@|$(INCLUDEDIR)|' \
	    -e 's|@VERSION@|$(VERSION)|' mk/brdfwave.pc.in >$(DESTDIR)$(PKGCONFIGDIR)/brdfwave.pc
	$(INSTALL) -m 644 docs/man/brdfwave.1 $(DESTDIR)$(MANDIR)/man1/
	$(INSTALL) -m 644 docs/man/libbrdfwave.3 $(DESTDIR)$(MANDIR)/man3/
	$(INSTALL) -m 644 $(PY_SOURCES) $(DESTDIR)$(PYTHONDIR)/brdfwave/
	printf '"""Written by make install: the library this package loads."""\nLIBRARY = "%s"\n' \
	    '$(PY_LIBRARY)' >$(DESTDIR)$(PYTHONDIR)/brdfwave/_libpath.py

uninstall:
	rm -f $(DESTDIR)$(BINDIR)/brdfwave $(DESTDIR)$(LIBDIR)/libbrdfwave.so.$(VERSION) \
	    $(DESTDIR)$(LIBDIR)/$(SONAME) $(DESTDIR)$(LIBDIR)/libbrdfwave.so \
	    $(DESTDIR)$(LIBDIR)/libbrdfwave.a $(DESTDIR)$(PKGCONFIGDIR)/brdfwave.pc \
	    $(DESTDIR)$(MANDIR)/man1/brdfwave.1 $(DESTDIR)$(MANDIR)/man3/libbrdfwave.3 \
	    $(addprefix $(DESTDIR)$(INCLUDEDIR)/brdfwave/,$(notdir $(PUBLIC_HEADERS)))
	rm -rf $(DESTDIR)$(PYTHONDIR)/brdfwave
	-rmdir $(DESTDIR)$(INCLUDEDIR)/brdfwave 2>/dev/null
