#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# make_initramfs.sh OUT KVER — the KMS test VM's initramfs (newc cpio, not
# compressed): busybox-static, the kernel modules for virtio-9p and the bochs
# DRM driver of kernel KVER (in load order, from kmod's modprobe --show-depends
# against /lib/modules/KVER: the installed linux-image-amd64, which need not be
# the running kernel), and guest_init.sh as /init.
set -euo pipefail
out=$1
kver=$2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

mkdir -p "$work"/{bin,dev,proc,sys,host,modules}
cp /bin/busybox "$work/bin/busybox"
for applet in sh mount insmod cat echo sleep poweroff chroot; do ln -s busybox "$work/bin/$applet"; done
cp "$here/guest_init.sh" "$work/init"
chmod 755 "$work/init"

# virtio_pci + 9pnet_virtio + 9p: the host root over virtio-9p; bochs pulls in
# drm, drm_kms_helper, ttm, drm_ttm_helper and drm_vram_helper.
modprobe -a -S "$kver" --show-depends virtio_pci 9pnet_virtio 9p bochs |
    awk '$1 == "insmod" && !seen[$2]++ { print $2 }' >"$work/modules.list"
: >"$work/modules/order"
while read -r ko; do
    name=$(basename "$ko")
    case "$name" in
    *.ko.xz) xz -dc "$ko" >"$work/modules/${name%.xz}"; name=${name%.xz} ;;
    *.ko.zst) zstd -qdc "$ko" >"$work/modules/${name%.zst}"; name=${name%.zst} ;;
    *) cp "$ko" "$work/modules/$name" ;;
    esac
    echo "$name" >>"$work/modules/order"
done <"$work/modules.list"
rm "$work/modules.list"
(cd "$work" && find . | LC_ALL=C sort | busybox cpio -o -H newc 2>/dev/null) >"$out"
