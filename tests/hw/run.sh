#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# VM tests of the I2C acquirers against real kernel drivers (make check-hw).
#
# Boots Debian 12's kernel (linux-image-amd64, 6.1) in qemu-system-x86_64
# (TCG, no KVM) with a busybox initramfs that loads i2c-stub (banked as the
# window of docs/I2C.md), i2c-dev, configfs and gpio-sim (built here out of
# tree from linux-source-6.1: Debian does not ship it), mounts this machine's
# root and this checkout read-only over 9p (the checkout at /tmp/checkout in
# the guest, wherever it is here) and runs tests/hw/guest.py there: Debian's
# python3, numpy, smbus2, gpiod and this tree's build are used as they are.
#
# Cached in $BW_HW_CACHE (default build/hw-cache): gpio-sim.ko and the
# initramfs, per kernel version. Prints the guest's case lines and
# "RESULT: N passed, M failed".
set -u
cd "$(dirname "$0")/../.."
ROOT=$PWD
BUILD=${BUILD:-build/host}
CACHE=${BW_HW_CACHE:-build/hw-cache}
VM_TIMEOUT=${BW_HW_TIMEOUT:-170}

fail() { echo "hw: $*"; echo "RESULT: 0 passed, 1 failed"; exit 1; }

# the newest Debian 6.1 kernel with its headers
kver=""
for d in $(ls -d /lib/modules/6.1.*-amd64 2>/dev/null | sort -V); do
    v=$(basename "$d")
    [ -f "/boot/vmlinuz-$v" ] && [ -d "$d/build" ] && kver=$v
done
[ -n "$kver" ] || fail "no Debian 6.1 kernel with headers (tests/deps.sh hw installs linux-image-amd64 and linux-headers-amd64)"
command -v qemu-system-x86_64 >/dev/null || fail "qemu-system-x86_64 missing (tests/deps.sh hw)"
[ -x "$BUILD/brdfwave" ] && [ -f "$BUILD/libbrdfwave.so" ] || fail "build first: make all"
MODS=/lib/modules/$kver/kernel
C=$CACHE/$kver
mkdir -p "$C"

# gpio-sim.ko: drivers/gpio/gpio-sim.c and kernel/irq/irq_sim.c in one module;
# irq_to_desc() is not exported, generic_handle_irq() does the same
if [ ! -f "$C/gpio-sim.ko" ]; then
    src=/usr/src/linux-source-6.1.tar.xz
    [ -f "$src" ] || fail "$src missing (tests/deps.sh hw installs linux-source-6.1)"
    w=$(mktemp -d)
    tar -xJf "$src" -C "$w" --strip-components=1 linux-source-6.1/drivers/gpio/gpio-sim.c \
        linux-source-6.1/drivers/gpio/gpiolib.h linux-source-6.1/kernel/irq/irq_sim.c ||
        fail "cannot extract gpio-sim from $src"
    mkdir "$w/m"
    cp "$w/drivers/gpio/gpio-sim.c" "$w/m/gpio-sim-main.c"
    cp "$w/drivers/gpio/gpiolib.h" "$w/m/"
    sed 's/handle_simple_irq(irq_to_desc(irqnum));/generic_handle_irq(irqnum);/' \
        "$w/kernel/irq/irq_sim.c" >"$w/m/irq_sim.c"
    grep -q 'generic_handle_irq(irqnum);' "$w/m/irq_sim.c" || fail "irq_sim.c: the line to patch changed"
    printf 'obj-m := gpio-sim.o\ngpio-sim-y := gpio-sim-main.o irq_sim.o\n' >"$w/m/Kbuild"
    if ! make -s -C "/lib/modules/$kver/build" M="$w/m" modules >"$w/build.log" 2>&1; then
        cat "$w/build.log"
        fail "gpio-sim did not build"
    fi
    cp "$w/m/gpio-sim.ko" "$C/gpio-sim.ko"
    rm -rf "$w"
fi

# initramfs: busybox, the modules in load order, tests/hw/init
ORDER="virtio_ring virtio virtio_pci_legacy_dev virtio_pci_modern_dev virtio_pci netfs fscache
9pnet 9pnet_virtio 9p configfs i2c-dev i2c-stub gpio-sim"
if [ ! -f "$C/initrd.gz" ] || [ tests/hw/init -nt "$C/initrd.gz" ] || [ "$0" -nt "$C/initrd.gz" ]; then
    command -v cpio >/dev/null || fail "cpio missing (tests/deps.sh hw)"
    w=$(mktemp -d)
    mkdir -p "$w/bin" "$w/dev" "$w/proc" "$w/sys" "$w/host" "$w/mods"
    cp /bin/busybox "$w/bin/busybox" || fail "busybox missing (busybox-static)"
    cp tests/hw/init "$w/init"
    chmod +x "$w/init"
    for m in $ORDER; do
        if [ "$m" = gpio-sim ]; then f=$C/gpio-sim.ko
        else f=$(find "$MODS" -name "$m.ko" | head -1); fi
        [ -n "$f" ] && [ -f "$f" ] || fail "module $m.ko not found for $kver"
        cp "$f" "$w/mods/$m.ko"
    done
    echo $ORDER >"$w/mods/order"
    (cd "$w" && find . | cpio -o -H newc 2>/dev/null | gzip -1) >"$C/initrd.gz.tmp" &&
        mv "$C/initrd.gz.tmp" "$C/initrd.gz"
    rm -rf "$w"
fi

# the payloads the test device offers (made by the codec on this machine)
D=$BUILD/hw
rm -rf "$D"
mkdir -p "$D"
B=$BUILD/brdfwave
"$B" synth --model phong --kd 0.6 --ks 0.3 --n 12 --level 3 --incoming 3 -o "$D/a.f32" &&
    "$B" encode -i "$D/a.f32" -o "$D/a.bwv" --bands 1 --level 3 --incoming 3 --max-error 0.002 >/dev/null &&
    "$B" encode --input-format sed -i tests/data/field_psr3500/*.sed -o "$D/b.bwv" --ratio 40 >/dev/null ||
    fail "cannot make the test payloads"

log=$D/console.log
timeout "$VM_TIMEOUT" qemu-system-x86_64 -machine q35 -accel tcg -m 1024 -smp 1 -nographic \
    -no-reboot -nic none -kernel "/boot/vmlinuz-$kver" -initrd "$C/initrd.gz" \
    -append "console=ttyS0 quiet panic=-1" \
    -virtfs local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap \
    -virtfs "local,path=${ROOT//,/,,},mount_tag=checkout,security_model=none,readonly=on,multidevs=remap" \
    </dev/null 2>&1 | sed -u 's/\r$//' | tee "$log" | grep -E '^(hw|ok|FAIL|RESULT|hw-init)|Error|assert' 
rc=${PIPESTATUS[0]}
if [ "$rc" = 124 ]; then
    echo "hw: the VM did not finish within $VM_TIMEOUT s (console: $log)"
fi
if ! grep -q '^RESULT: [0-9]* passed, [0-9]* failed' "$log"; then
    echo "---- console (last 40 lines) ----"
    tail -40 "$log"
    fail "the guest tests did not report"
fi
grep -q '^RESULT: [0-9]* passed, 0 failed' "$log" || { sed -n '/^FAIL/,/^ok /p' "$log" | head -60; exit 1; }
