#!/usr/bin/env bash
# One-way dependencies between the rooms of a source tree (issue 37; docs/hacking.md): a file may
# include the headers of, and call into, its own room and the rooms below it, never one above;
# and no files form a circle.
#   tools/layers.sh [-v] [-I INCDIR]... ROOT OBJDIR
# ROOT/rooms.txt lists the rooms, ground floor first, one a line: NAME FOLDER (relative to ROOT,
# "." for the files directly in it) and what the room holds; a line "+ FILE what" names a header
# every room may include (include/sbfx.h, the public types). Every .c and .h under ROOT must be in a
# room. Includes are read from the sources: a "quoted" name is looked up in each INCDIR (the
# tree's -I folders; default ROOT), then in the including file's folder; one that resolves
# outside ROOT, or nowhere, is not the tree's. Calls are read from the objects: OBJDIR mirrors
# ROOT (ROOT/ROOM/NAME.c -> OBJDIR/ROOM/NAME.o), and an object's undefined symbol that another
# object of the tree defines is a call (or a use of its data) from that file into the other.
# Objects not built yet are counted and skipped. A circle: files that reach one another through
# includes and calls, in one room or across rooms.
# Prints one line per finding ("upward include: A (room) -> B (room)", "upward call: A (room) ->
# B (room): SYMBOL", "circle: A B ...", "not in a room: F") and a summary; -v also prints every
# dependency ("FROM TO include|call NAME"). Exits 1 on a finding, 2 on bad usage.
set -u
verbose=0 incdirs=()
while [ $# -gt 0 ]; do
    case $1 in
        -v) verbose=1 ;;
        -I) incdirs+=("${2%/}"); shift ;;
        -I*) incdirs+=("${1#-I}") ;;
        *) break ;;
    esac
    shift
done
[ $# -eq 2 ] || { echo "usage: tools/layers.sh [-v] [-I INCDIR]... ROOT OBJDIR" >&2; exit 2; }
root=${1%/} objdir=${2%/}
[ ${#incdirs[@]} -gt 0 ] || incdirs=("$root")
[ -f "$root/rooms.txt" ] || { echo "layers: $root/rooms.txt is missing" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# rooms: "LEVEL NAME FOLDER", ground floor 0; shared headers: "FILE"
awk -v shared="$tmp/shared" '/^[ \t]*(#|$)/ { next } $1 == "+" { print $2 > shared; next } { print n++, $1, $2 }' \
    "$root/rooms.txt" >"$tmp/rooms"
touch "$tmp/shared"

# files: "PATH LEVEL ROOM", PATH relative to ROOT; the unplaced ones apart
(cd "$root" && find . \( -name '*.c' -o -name '*.h' \) -type f | sed 's|^\./||' | sort) >"$tmp/all"
awk -v unplaced="$tmp/unplaced" 'FILENAME == ARGV[1] { level[$3] = $1; name[$3] = $2; next }
     FILENAME == ARGV[2] { shared[$1] = 1; next }
     {
        dir = $0; if (!sub(/\/[^\/]*$/, "", dir)) dir = "."
        if ($0 in shared) print $0, -1, "shared"
        else if (dir in level) print $0, level[dir], name[dir]
        else print $0 > unplaced
     }' "$tmp/rooms" "$tmp/shared" "$tmp/all" >"$tmp/files"
touch "$tmp/unplaced"

# includes: every quoted #include of the tree's files, resolved (one pass over all sources)
(cd "$root" && xargs -a "$tmp/all" grep -H '^[[:space:]]*#[[:space:]]*include[[:space:]]*"') |
    sed 's/^\([^:]*\):[^"]*"\([^"]*\)".*/\1 \2/' >"$tmp/includes"
printf '%s\n' "${incdirs[@]}" >"$tmp/incdirs"
awk -v root="$root" '
    function norm(p,   n, i, k, part, out) {
        n = split(p, part, "/"); k = 0
        for (i = 1; i <= n; i++) {
            if (part[i] == "." || part[i] == "") continue
            if (part[i] == "..") { if (k > 0) k--; else return ""; continue }
            stack[++k] = part[i]
        }
        out = ""; for (i = 1; i <= k; i++) out = out (i > 1 ? "/" : "") stack[i]
        return out
    }
    FILENAME == ARGV[1] { known[$1] = 1; next }
    FILENAME == ARGV[2] { inc[++ninc] = $1; next }
    {
        file = $1; name = $2; target = ""
        for (i = 1; i <= ninc && target == ""; i++) {
            full = norm(inc[i] "/" name); r = norm(root)
            if (index(full, r "/") == 1 && (substr(full, length(r) + 2) in known)) target = substr(full, length(r) + 2)
        }
        if (target == "") {
            dir = file; if (!sub(/\/[^\/]*$/, "", dir)) dir = "."
            cand = norm(dir "/" name)
            if (cand in known) target = cand
        }
        if (target != "" && target != file) print file, target, "include", name
    }' "$tmp/all" "$tmp/incdirs" "$tmp/includes" >"$tmp/edges"

# calls: the objects' symbols (one nm over every object that is built)
missing=0
: >"$tmp/objects"
while read -r file; do
    case $file in *.c) ;; *) continue ;; esac
    if [ -f "$objdir/${file%.c}.o" ]; then echo "$objdir/${file%.c}.o $file" >>"$tmp/objects"
    else missing=$((missing + 1)); fi
done <"$tmp/all"
objects=$(wc -l <"$tmp/objects")
if [ "$objects" -gt 0 ]; then
    cut -d' ' -f1 "$tmp/objects" | xargs nm -A 2>/dev/null |
        awk 'NR == FNR { src[$1] = $2; next }
             {
                colon = index($0, ":"); obj = substr($0, 1, colon - 1); n = split(substr($0, colon + 1), f, " ")
                if (n == 2 && f[1] == "U") print "U", src[obj], f[2]
                else if (n == 3 && f[2] ~ /^[TDBRVWGSC]$/) print "D", src[obj], f[3]
             }' "$tmp/objects" - >"$tmp/symbols"
    awk '$1 == "D" { def[$3] = $2; next } ($3 in def) && def[$3] != $2 { print $2, def[$3], "call", $3 }' \
        <(grep '^D' "$tmp/symbols") <(grep '^U' "$tmp/symbols") >>"$tmp/edges"
fi

# upward dependencies, and the counts
awk -v counts="$tmp/counts" 'NR == FNR { level[$1] = $2; room[$1] = $3; next }
     {
        n[$3]++
        if (level[$2] > level[$1])
            printf "upward %s: %s (%s) -> %s (%s)%s\n", $3, $1, room[$1], $2, room[$2], $3 == "call" ? ": " $4 : ""
     }
     END { printf "%d includes, %d calls", n["include"], n["call"] > counts }' \
    "$tmp/files" "$tmp/edges" >"$tmp/findings"

# circles: drop the files that reach no file still in the graph, then those no file still in it
# reaches, until nothing changes; what is left lies on a circle (or between two)
awk '{ key = $1 SUBSEP $2; if (!(key in seen)) { seen[key] = 1; out[$1]++; inn[$2]++; from[++m] = $1; to[m] = $2 }
       node[$1] = node[$2] = 1 }
     END {
        do {
            changed = 0
            for (v in node) if (!out[v] || !inn[v]) {
                delete node[v]; changed = 1
                for (i = 1; i <= m; i++) if (from[i] != "" && (from[i] == v || to[i] == v)) {
                    out[from[i]]--; inn[to[i]]--; from[i] = to[i] = ""
                }
            }
        } while (changed)
        s = ""; for (v in node) s = s " " v
        if (s != "") print "circle:" s
     }' "$tmp/edges" >>"$tmp/findings"
sed 's/^/not in a room: /' "$tmp/unplaced" >>"$tmp/findings"

[ "$verbose" -eq 1 ] && sort -u "$tmp/edges"
findings=$(wc -l <"$tmp/findings")
cat "$tmp/findings"
not_built=""
[ "$missing" -gt 0 ] && not_built=", $missing not built: their calls unread"
echo "layers: $root: $(wc -l <"$tmp/files") files in $(wc -l <"$tmp/rooms") rooms, $(cat "$tmp/counts")" \
    "($objects objects read$not_built): $findings finding(s)"
[ "$findings" -eq 0 ]
