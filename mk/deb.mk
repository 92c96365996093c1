# SPDX-License-Identifier: BSD-2-Clause
# make deb: the Debian packages (debian/) built with dpkg-buildpackage from
# a copy of the tree in build/deb/src; the .deb files land in build/deb/.
DEB_DIR := build/deb

deb:
	$(Q)rm -rf $(DEB_DIR) && mkdir -p $(DEB_DIR)/src
	$(Q)git ls-files -co --exclude-standard -z | xargs -0 cp --parents -t $(DEB_DIR)/src 2>/dev/null || \
	    tar -c --exclude=./build --exclude=./.git . | tar -x -C $(DEB_DIR)/src
	$(Q)cd $(DEB_DIR)/src && dpkg-buildpackage -us -uc -b >../build.log 2>&1 || \
	    { tail -30 ../build.log; exit 1; }
	$(Q)ls $(DEB_DIR)/*.deb

.PHONY: deb
