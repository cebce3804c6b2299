# Busy processes for the scripts that measure under load, sourced by them: each keeps one core busy while the runs go.
#
#   busy_option OPT   in the script's getopts loop: -l (two busy processes, as many as this 2-core machine has
#                     cores) or -b BUSY (OPTARG) sets busy_count
#   busy_start        starts busy_count busy processes
#   busy_stop         kills them: call it from the script's EXIT trap
busy_count=0
busy_pids=()

busy_option() {
    case $1 in
        l) busy_count=2 ;;
        b) busy_count=$OPTARG ;;
    esac
}

busy_start() {
    if [ "$busy_count" -gt 0 ]; then
        for _ in $(seq 1 "$busy_count"); do
            sh -c 'while :; do :; done' &
            busy_pids+=($!)
        done
    fi
}

busy_stop() {
    for pid in "${busy_pids[@]}"; do kill "$pid" 2>/dev/null || true; done
}
