# shellcheck shell=sh
# Sourced (". tools/debian-archive.sh"), not run: the Debian archive this machine's apt uses,
# read at run time (no archive host is written in the repository), and apt-get with a private
# state (its own sources list, package lists and cache under a folder of the build), so the
# machine's own package lists stay as they are. Used by tools/mesa-shim.sh (Debian 13's Mesa
# source) and tools/web-libconfig.sh (libconfig's C source for the WebGL 2 build).

# The machine's Debian codename (bookworm, trixie, ...).
debian_codename() {
    sed -n 's/^VERSION_CODENAME=//p' /etc/os-release 2>/dev/null | head -n 1
}

# The archive URI of the stanza that serves SUITE (default: the machine's codename; not
# -security) in the deb822 sources file, or of the first deb line of a one-line sources.list.
debian_archive_uri() {
    _da_suite=${1:-$(debian_codename)}
    _da_src=/etc/apt/sources.list.d/debian.sources
    _da_uri=""
    if [ -r "$_da_src" ] && [ -n "$_da_suite" ]; then
        _da_uri=$(awk -v suite="$_da_suite" 'BEGIN{RS=""} $0 ~ ("Suites:[^\n]*" suite "([ \n]|$)") && !/security/ {
                  if (match($0, /URIs: *[^ \n]+/)) { s = substr($0, RSTART, RLENGTH);
                  sub(/URIs: */, "", s); print s; exit } }' "$_da_src")
    fi
    if [ -z "$_da_uri" ] && [ -r /etc/apt/sources.list ]; then
        _da_uri=$(awk '$1 == "deb" && $0 !~ /security/ { for (i = 2; i <= NF; i++)
                  if ($i ~ /^[a-z]+:\/\//) { print $i; exit } }' /etc/apt/sources.list)
    fi
    [ -n "$_da_uri" ] || { echo "debian-archive: no Debian archive URI in /etc/apt/sources.list.d/debian.sources or /etc/apt/sources.list" >&2; return 1; }
    echo "$_da_uri"
}

# debian_private_apt DIR ARGS...: apt-get with its sources list DIR/sources.list (written by
# debian_private_sources) and its lists and cache under DIR.
debian_private_apt() {
    _da_dir=$1
    shift
    # as root apt would download as _apt, who may not write into the build folder
    _da_sandbox=""
    [ "$(id -u)" -ne 0 ] || _da_sandbox="-o APT::Sandbox::User=root"
    # shellcheck disable=SC2086 # $_da_sandbox is one option or none
    apt-get -q -o Dir::Etc::SourceList="$_da_dir/sources.list" -o Dir::Etc::SourceParts=/dev/null \
        -o Dir::State::Lists="$_da_dir/lists" -o Dir::Cache="$_da_dir/cache" \
        -o Dir::State::Status=/var/lib/dpkg/status $_da_sandbox "$@"
}

# debian_private_sources DIR SUITE: DIR/sources.list with the deb and deb-src lines of SUITE
# from the machine's archive, and its package lists (apt-get update).
debian_private_sources() {
    mkdir -p "$1/lists/partial" "$1/cache/archives/partial"
    _da_uri=$(debian_archive_uri "$(debian_codename)") || return 1
    printf 'deb %s %s main\ndeb-src %s %s main\n' "$_da_uri" "$2" "$_da_uri" "$2" > "$1/sources.list"
    debian_private_apt "$1" update >&2
}
