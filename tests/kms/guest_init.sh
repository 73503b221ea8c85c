#!/bin/sh
# SPDX-License-Identifier: MIT
# PID 1 of the KMS test VM (tests/kms/run_vm_test.sh): loads the modules in
# order, mounts the host's root read-only over virtio-9p at /host with the
# guest's own /proc, /sys and /dev and the test's output folder (snell_out=DIR,
# shared read-write as tag "out") at its own path, runs the script the kernel
# command line names (snell_run=PATH, a host path; the kernel hands unknown
# key=value parameters to init as environment variables) inside /host, and
# powers off.
export PATH=/bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
echo "KMS-VM: init after $(cut -d' ' -f1 /proc/uptime) s"
while read -r m; do
    insmod "/modules/$m" || echo "KMS-VM: insmod $m failed"
done </modules/order
if mount -t 9p -o trans=virtio,version=9p2000.L,ro,msize=512000,cache=loose hostroot /host; then
    mount -t proc proc /host/proc
    mount -t sysfs sys /host/sys
    mount -t devtmpfs dev /host/dev
    mount -t 9p -o trans=virtio,version=9p2000.L,msize=512000 out "/host$snell_out" ||
        echo "KMS-VM: cannot mount the output folder $snell_out"
    echo "KMS-VM: host root mounted after $(cut -d' ' -f1 /proc/uptime) s"
    chroot /host /bin/sh "$snell_run"
    echo "KMS-VM: guest script exit $?"
else
    echo "KMS-VM: cannot mount the host root over 9p"
fi
poweroff -f
