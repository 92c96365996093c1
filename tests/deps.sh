#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# Installs the Debian packages a make goal needs, when they are missing.
#   tests/deps.sh [check|hw|run|device|bench|fuzz|reproduce]   (default: check)
set -eu
goal=${1:-check}
# the VM tests of the I2C acquirers (tests/hw/run.sh) and brdfwave acquire
hw="libgpiod-dev python3-libgpiod python3-smbus2 i2c-tools qemu-system-x86 linux-image-amd64
    linux-headers-amd64 linux-source-6.1 busybox-static cpio xz-utils python3-numpy"
case "$goal" in
check) pkgs="gcc make libc6-dev libcmocka-dev zlib1g-dev gcc-arm-none-eabi libnewlib-arm-none-eabi
             gcc-riscv64-unknown-elf binutils-riscv64-unknown-elf qemu-system-arm python3
             python3-numpy python3-pywt python3-venv python3-pip python3-matplotlib pkg-config
             man-db dpkg-dev debhelper dh-python fakeroot lintian $hw" ;;
hw)    pkgs="$hw" ;;
run)   pkgs="gcc make libc6-dev zlib1g-dev bc gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm" ;;
device) pkgs="gcc make libc6-dev zlib1g-dev gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm
             python3 python3-numpy" ;;
bench) pkgs="gcc make libc6-dev zlib1g-dev libcharls-dev libopenjp2-tools zfp fpzip-utils libaec-tools xz-utils zstd
             python3 python3-numpy python3-matplotlib" ;;
fuzz)  pkgs="clang libclang-rt-14-dev" ;;
reproduce) pkgs="gcc make libc6-dev zlib1g-dev python3 python3-numpy python3-matplotlib" ;;
*) echo "tests/deps.sh: unknown goal '$goal'" >&2; exit 2 ;;
esac

missing=""
for p in $pkgs; do
    # a package counts as present when dpkg says it is installed
    st=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
    case "$st" in *"install ok installed"*) ;; *) missing="$missing $p" ;; esac
done
[ -z "$missing" ] && exit 0

echo "installing Debian packages:$missing"
sudo=""
if [ "$(id -u)" != 0 ]; then
    command -v sudo >/dev/null || { echo "tests/deps.sh: need root (or sudo) to install:$missing" >&2; exit 1; }
    sudo=sudo
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q >/dev/null
# shellcheck disable=SC2086
$sudo apt-get install -y -q --no-install-recommends $missing >/dev/null
