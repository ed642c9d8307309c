# Sourced by the bench scripts: `wall COMMAND...` prints the wall seconds COMMAND took (two
# decimals), its output kept in "$out/log" (the sourcing script sets $out, a scratch
# directory), and fails as COMMAND does.
wall() {
    local t0 t1 status=0
    t0=$(date +%s.%N)
    "$@" > "$out/log" 2>&1 || status=$?
    t1=$(date +%s.%N)
    awk "BEGIN { printf \"%.2f\", $t1 - $t0 }"
    return $status
}
