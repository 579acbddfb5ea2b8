#!/bin/sh
# slurm-sequence: docs/sequences/luz-sequence.sbatch run for real on a
# Slurm of one node that this test starts itself (Debian's slurm-wlm and
# munge), and its frames checked byte for byte against luz-render's own
# frames of the same sequence rendered in one run.
#
# Usage: slurm_sequence.sh SOURCE_ROOT LUZ_RENDER
#
# The recipe is submitted as it is but for the size of the sequence: its
# luz-render line's --frames 2400 ... --size 3840x2160 becomes --frames 12
# ... --size 64x36, and sbatch is given --array=0-3 with SHARDS=4, so four
# array tasks render four shards. Everything runs in a temporary folder:
# munged with its own key and socket, slurmctld and slurmd with their own
# slurm.conf (one node, 4 CPUs declared over this machine's, ports
# chosen free), state and logs. Every wait has a deadline; the daemons are
# stopped and the folder removed on any exit. Exit 77 (skipped) with the
# reason where it cannot start: not root (slurmd starts jobs as their
# user), or slurm-wlm or munge missing (tools/install-deps test installs
# them).
set -u

root=$1
# absolute: meson gives it relative to the build folder, and the job and
# the one run below start elsewhere
luz_render=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
recipe=$root/docs/sequences/luz-sequence.sbatch

skip() { echo "slurm-sequence: skipped: $*"; exit 77; }
fail() {
    echo "slurm-sequence: FAILED: $*" >&2
    for log in "$work"/*.log "$work"/run/logs/*.log; do
        [ -f "$log" ] && { echo "--- $log" >&2; tail -n 20 "$log" >&2; }
    done
    exit 1
}

[ "$(id -u)" = 0 ] || skip "needs root: slurmd runs each job as the user who submitted it"
for program in munged slurmctld slurmd sbatch scontrol sinfo; do
    command -v "$program" >/dev/null 2>&1 ||
        skip "no $program (Debian's slurm-wlm and munge: tools/install-deps test)"
done
[ -f "$recipe" ] || fail "no recipe at $recipe"

work=$(mktemp -d "${TMPDIR:-/tmp}/luz-slurm-XXXXXX") || exit 1
chmod 0700 "$work"
pids=""
cleanup() {
    # jobs first (their steps outlive slurmd), while slurmctld still answers
    [ -n "$pids" ] && [ -f "$work/slurm.conf" ] &&
        SLURM_CONF="$work/slurm.conf" timeout 5 scancel --quiet --partition=luztest 2>/dev/null
    for pid in $pids; do kill "$pid" 2>/dev/null; done
    for pid in $pids; do
        i=0
        while kill -0 "$pid" 2>/dev/null && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
        kill -9 "$pid" 2>/dev/null
    done
    rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP

# Waits up to $1 tenths of a second for the command after it to succeed.
wait_for() {
    limit=$1
    shift
    i=0
    until "$@" >/dev/null 2>&1; do
        i=$((i + 1))
        [ $i -ge "$limit" ] && return 1
        sleep 0.1
    done
}

# A TCP port nothing listens on (the kernel's choice, then let go).
free_port() {
    python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

# ---- munge: its own key, socket and files ----
dd if=/dev/urandom of="$work/munge.key" bs=1024 count=1 2>/dev/null
chmod 0400 "$work/munge.key"
socket=$work/munge.socket
munged --foreground --force --key-file="$work/munge.key" --socket="$socket" \
    --pid-file="$work/munged.pid" --seed-file="$work/munged.seed" \
    --log-file="$work/munged.log" >"$work/munged.out" 2>&1 &
pids="$pids $!"
wait_for 100 test -S "$socket" || fail "munged did not open its socket in 10 s"

# ---- slurm.conf: one node, this machine ----
node=$(hostname -s)
user=$(id -un)
mkdir "$work/state" "$work/spool" "$work/run"
ctld_port=$(free_port)
slurmd_port=$(free_port)
[ "$ctld_port" != "$slurmd_port" ] || slurmd_port=$((slurmd_port + 1))
cat >"$work/slurm.conf" <<EOF
ClusterName=luztest
SlurmctldHost=$node(127.0.0.1)
SlurmUser=$user
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
SlurmdParameters=config_overrides
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
NodeName=$node NodeAddr=127.0.0.1 CPUs=4 State=UNKNOWN
PartitionName=luztest Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$work/slurm.conf"

slurmctld -D -i -f "$SLURM_CONF" >"$work/slurmctld.out" 2>&1 &
pids="$pids $!"
wait_for 150 scontrol ping || fail "slurmctld did not answer in 15 s"
slurmd -D -f "$SLURM_CONF" -N "$node" >"$work/slurmd.out" 2>&1 &
pids="$pids $!"
node_idle() { sinfo -h -N -o %t | grep -qx idle; }
wait_for 200 node_idle || fail "the node did not become idle in 20 s: $(sinfo -h -N -o '%t %E')"

# ---- the recipe, submitted; luz-render on the job's PATH ----
mkdir "$work/bin" "$work/run/logs" "$work/one"
ln -s "$luz_render" "$work/bin/luz-render"
sed -e 's|--frames 2400 --fps 24 --size 3840x2160|--frames 12 --fps 24 --size 64x36|' \
    "$recipe" >"$work/run/luz-sequence.sbatch"
grep -q -- '--frames 12 --fps 24 --size 64x36' "$work/run/luz-sequence.sbatch" ||
    fail "the recipe's luz-render line has changed: update this test's substitution"
(cd "$work/run" && PATH="$work/bin:$PATH" SHARDS=4 timeout 60 \
    sbatch --wait --array=0-3 luz-sequence.sbatch) >"$work/sbatch.out" 2>&1 ||
    fail "sbatch --wait failed: $(cat "$work/sbatch.out")"

# ---- luz-render's own frames, in one run, against the array's ----
(cd "$work/one" && "$luz_render" --frames 12 --fps 24 --size 64x36 -o lab_%05d.png) ||
    fail "luz-render in one run failed"
[ "$(ls "$work/run/frames" | wc -l)" = 12 ] ||
    fail "the array wrote $(ls "$work/run/frames" | wc -l) files, expected 12: $(ls "$work/run/frames")"
for k in 0 1 2 3 4 5 6 7 8 9 10 11; do
    name=$(printf 'lab_%05d.png' "$k")
    cmp -s "$work/one/$name" "$work/run/frames/$name" || fail "$name differs from luz-render's own"
done
[ "$(ls "$work/run/logs" | wc -l)" = 4 ] || fail "expected 4 task logs: $(ls "$work/run/logs")"
echo "slurm-sequence: 4 array tasks on a one-node Slurm wrote the 12 frames of one run, byte for byte"
