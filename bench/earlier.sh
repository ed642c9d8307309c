# Sourced by the bench scripts that time the checked-out build against an earlier one (they
# run from the repository's root): `earlier_worktree REVISION` checks REVISION out in a
# temporary git worktree ($worktree) and makes a scratch directory ($out), both removed when
# the script exits; `earlier_build ARGS…` runs `cargo build --release --quiet ARGS…` in that
# worktree into target/earlier (kept between runs: only the first build takes minutes);
# `median` prints the median of the numbers on its input, one a line; `grinlight_of BUILD`
# prints the binary of the `current` (checked-out) or the `earlier` build.
earlier_worktree() {
    worktree=$(mktemp -d)
    out=$(mktemp -d)
    trap 'git worktree remove --force "$worktree"; rm -rf "$worktree" "$out"' EXIT
    git worktree add --quiet --detach "$worktree" "$1"
}
earlier_build() {
    (cd "$worktree" && CARGO_TARGET_DIR="$OLDPWD/target/earlier" cargo build --release --quiet "$@")
}
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
grinlight_of() {
    case $1 in
        current) echo target/release/grinlight ;;
        earlier) echo target/earlier/release/grinlight ;;
    esac
}
