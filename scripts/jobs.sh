#!/usr/bin/env bash
# Prints how many jobs to build and test with: the processors this process may run on (nproc),
# no more than a CPU quota set on its control group allows (a container may see every core of
# its host and be allowed two: 64 compilers then share two cores and 24 GiB), nor one per 1.5 GiB
# of memory (a compile of the lens code takes up to about 1 GiB). At least 1.
set -euo pipefail
jobs=$(nproc)
quota=""
if [ -r /sys/fs/cgroup/cpu.max ]; then  # cgroup v2: "QUOTA PERIOD" or "max PERIOD"
  read -r q p < /sys/fs/cgroup/cpu.max
  [ "$q" != max ] && quota=$(( (q + p - 1) / p ))
elif [ -r /sys/fs/cgroup/cpu/cpu.cfs_quota_us ]; then  # cgroup v1: -1 when unlimited
  q=$(cat /sys/fs/cgroup/cpu/cpu.cfs_quota_us)
  p=$(cat /sys/fs/cgroup/cpu/cpu.cfs_period_us)
  [ "$q" -gt 0 ] && quota=$(( (q + p - 1) / p ))
fi
if [ -n "$quota" ] && [ "$quota" -lt "$jobs" ]; then jobs=$quota; fi
memory_kib=$(awk '/^MemAvailable:/ {print $2}' /proc/meminfo)
by_memory=$(( memory_kib / (1536 * 1024) ))
if [ "$by_memory" -lt "$jobs" ]; then jobs=$by_memory; fi
if [ "$jobs" -lt 1 ]; then jobs=1; fi
echo "$jobs"
