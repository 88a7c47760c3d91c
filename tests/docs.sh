#!/usr/bin/env bash
# The documentation's checks (issue 19), in `make test`:
#   docs/links/FILE    every relative link and image of FILE (README.md, docs/**/*.md) names a
#                      file or folder that exists; a #anchor names a heading of the Markdown
#                      file it points to (GitHub's anchors: lower case, punctuation dropped,
#                      spaces to hyphens, -1, -2... for repeats). Links in code are not links.
#   docs/example/FILE:LINE
#                      a fenced code block right after a line `<!-- example: PATH -->` is exactly
#                      the file PATH (relative to the repository root); after
#                      `<!-- example: PATH:A-B -->` exactly its lines A to B (1-based,
#                      inclusive). PATH must be built by the tests: named (it or its folder) in
#                      the Makefile, .ci/ or a test script.
#   docs/make-help     `make help` lists every .PHONY target a user runs.
#   docs/make-help-whole
#                      `make help` prints each entry whole: every comment line of the Makefile's
#                      "#   make" entries, none stopping mid-sentence.
#   docs/rooms/TREE    docs/hacking.md's map of TREE's rooms (src, player, net) names the rooms and
#                      folders of TREE/rooms.txt, in its order
#   docs/walkthrough/TITLE
#                      each step of a walkthrough of docs/hacking.md ("## Adding ..."): every path
#                      it gives in backquotes exists; one followed by "(ROOM)" lies in that room
#                      (src/ and platform/player/: their rooms.txt; include/sbfx.h: public); every
#                      name it gives in backquotes (a C identifier) occurs in one of its files
#   docs/requirements  README's Requirements name the packages make test-fresh's bare root has.
# Usage: tests/docs.sh. Prints "ok - docs/..." / "not ok - docs/...: why"; exits 1 on a failure.
set -u
cd "$(dirname "$0")/.." || exit 1

failures=0
ok() { echo "ok - docs/$1"; }
not_ok() {
    echo "not ok - docs/$1: $2"
    failures=$((failures + 1))
}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# md_scan FILE: one line per link ("L<TAB>line<TAB>target"), per example marker
# ("E<TAB>line<TAB>spec<TAB>first<TAB>last", the block's content lines; first > last: empty;
# first = 0: no block follows) and per heading ("H<TAB>line<TAB>anchor"), outside fenced code.
md_scan() {
    awk -v OFS='\t' '
    function slug(s) {
        s = tolower(s)
        gsub(/[^a-z0-9 _-]/, "", s)
        gsub(/ /, "-", s)
        return s
    }
    function fence_of(l) {
        if (match(l, /^ ? ? ?(```+|~~~+)/)) { f = substr(l, RSTART, RLENGTH); sub(/^ +/, "", f); return f }
        return ""
    }
    {
        line = $0
        f = fence_of(line)
        if (infence) {
            if (f != "" && substr(f, 1, 1) == substr(fencechar, 1, 1) && length(f) >= length(fencechar) && line ~ /^ ? ? ?(```+|~~~+)[ \t]*$/) {
                infence = 0
                if (pending) { print "E", markline, spec, first, NR - 1; pending = 0 }
            }
            next
        }
        if (f != "") {
            infence = 1; fencechar = f
            if (pending && NR == markline + 1) first = NR + 1
            else if (pending) { print "E", markline, spec, 0, 0; pending = 0 }
            next
        }
        if (pending) { print "E", markline, spec, 0, 0; pending = 0 }
        if (match(line, /^<!-- example: [^ ]+ -->[ \t]*$/)) {
            spec = line; sub(/^<!-- example: /, "", spec); sub(/ -->[ \t]*$/, "", spec)
            pending = 1; markline = NR
            next
        }
        if (line ~ /^#+ /) {
            h = line; sub(/^#+ +/, "", h); sub(/ +#* *$/, "", h)
            gsub(/`/, "", h)
            s = slug(h)
            n = seen[s]++
            print "H", NR, (n ? s "-" n : s)
        }
        gsub(/`[^`]*`/, "", line)        # inline code is not a link
        rest = line
        while (match(rest, /\]\([^)]*\)/)) {
            t = substr(rest, RSTART + 2, RLENGTH - 3)
            sub(/[ \t]+".*$/, "", t)       # [x](path "title")
            print "L", NR, t
            rest = substr(rest, RSTART + RLENGTH)
        }
        if (match(line, /^ ? ? ?\[[^]]+\]:[ \t]+[^ \t]+/)) {
            t = line; sub(/^ *\[[^]]+\]:[ \t]+/, "", t); sub(/[ \t].*$/, "", t)
            print "L", NR, t
        }
        rest = line
        while (match(rest, /(src|href)="[^"]*"/)) {
            t = substr(rest, RSTART, RLENGTH); sub(/^[a-z]+="/, "", t); sub(/"$/, "", t)
            print "L", NR, t
            rest = substr(rest, RSTART + RLENGTH)
        }
    }
    END { if (pending) print "E", markline, spec, 0, 0 }' "$1"
}

# built_by_tests PATH: the file or its folder is named where the tests are built and run.
built_by_tests() {
    local path=$1 dir
    dir=$(dirname "$path")
    grep -rqsF -- "$path" Makefile .ci tests --exclude=docs.sh && return 0
    grep -rqsF -- "$dir/" Makefile .ci tests --exclude=docs.sh
}

check_links() {
    local md=$1 scan=$2 dir problems="" count=0 kind line target path anchor resolved
    dir=$(dirname "$md")
    while IFS=$'\t' read -r kind line target; do
        [ "$kind" = L ] || continue
        case "$target" in
            "" | *://* | mailto:* | data:*) continue ;;
        esac
        count=$((count + 1))
        path=${target%%#*}
        anchor=""
        [ "$path" != "$target" ] && anchor=${target#*#}
        if [ -z "$path" ]; then
            resolved=$md
        else
            resolved=$dir/$path
            if [ ! -e "$resolved" ]; then
                problems="$problems; line $line: '$target' does not exist"
                continue
            fi
        fi
        if [ -n "$anchor" ]; then
            case "$resolved" in
                *.md)
                    if ! md_scan "$resolved" | awk -F'\t' -v a="$anchor" '$1 == "H" && $3 == a { f = 1 } END { exit !f }'; then
                        problems="$problems; line $line: '$target': no heading with the anchor #$anchor"
                    fi
                    ;;
            esac
        fi
    done <"$scan"
    if [ -z "$problems" ]; then
        ok "links/$md ($count links)"
    else
        not_ok "links/$md" "${problems#; }"
    fi
}

check_examples() {
    local md=$1 scan=$2 kind line spec first last path range a b name
    while IFS=$'\t' read -r kind line spec first last; do
        [ "$kind" = E ] || continue
        name="example/$md:$line"
        path=$spec
        range=""
        if [[ "$spec" =~ ^(.+):([0-9]+)-([0-9]+)$ ]]; then
            path=${BASH_REMATCH[1]}
            a=${BASH_REMATCH[2]}
            b=${BASH_REMATCH[3]}
            range="$a-$b"
        fi
        if [ "$first" -eq 0 ]; then
            not_ok "$name" "'<!-- example: $spec -->' is not followed by a fenced code block"
            continue
        fi
        if [ ! -f "$path" ]; then
            not_ok "$name" "$path does not exist"
            continue
        fi
        if [ -n "$range" ]; then
            if [ "$a" -lt 1 ] || [ "$b" -lt "$a" ] || [ "$b" -gt "$(wc -l <"$path")" ]; then
                not_ok "$name" "lines $range are not within $path ($(wc -l <"$path") lines)"
                continue
            fi
            sed -n "${a},${b}p" "$path" >"$tmp/want"
        else
            cat "$path" >"$tmp/want"
        fi
        if [ "$first" -le "$last" ]; then sed -n "${first},${last}p" "$md" >"$tmp/got"; else : >"$tmp/got"; fi
        if ! cmp -s "$tmp/want" "$tmp/got"; then
            local where
            where=$(diff "$tmp/want" "$tmp/got" | head -n 1)
            not_ok "$name" "the block (lines $first-$last) differs from $spec (diff: $where)"
        elif ! built_by_tests "$path"; then
            not_ok "$name" "$path is not built by the tests (named in no test script, .ci/ or the Makefile)"
        else
            ok "$name ($spec)"
        fi
    done <"$scan"
}

# make help prints the Makefile's "#   make TARGET" comment lines: every target a user runs
# (the .PHONY ones but the steps others call) must be among them.
check_make_help() {
    local help missing="" t
    help=$(make --no-print-directory help 2>&1)
    for t in $(sed -n 's/^\.PHONY://p' Makefile); do
        case "$t" in deps | lib | test-unit | test-gl | test-asan | test-platform | test-build | test-build-normal | test-build-asan | install-kiosk | uninstall-kiosk | install-gstreamer | uninstall-gstreamer | FORCE) continue ;; esac
        printf '%s\n' "$help" | grep -q "^make \(\[\)\?$t\b" || missing="$missing $t"
    done
    if [ -z "$missing" ]; then
        ok "make-help ($(printf '%s\n' "$help" | wc -l) lines)"
    else
        not_ok make-help "make help does not list:$missing (a '#   make TARGET  what' line at the Makefile's top)"
    fi
}
check_make_help

# make help says each target whole (issue 46): every "#   make" entry at the Makefile's top with
# all the comment lines that go on with it (indented under its text), and each entry ends where
# its sentence does: parentheses closed, not on a comma, colon or semicolon or on a word that
# wants more (and, or, the, of...). Prints the entries that do not.
help_entries() { # help_entries: one line per entry of make help's output on stdin, spaces collapsed
    awk '/^make / { if (e != "") print e; e = $0; next } /^ +[^ ]/ { t = $0; sub(/^ +/, "", t); e = e " " t; next }
        END { if (e != "") print e }' | tr -s ' '
}
makefile_entries() { # the same from the Makefile's comments
    awk '/^#   make / { if (e != "") print e; e = substr($0, 5); on = 1; next }
        on && /^#     / { t = $0; sub(/^# +/, "", t); e = e " " t; next }
        { if (e != "") print e; e = ""; on = 0 } END { if (e != "") print e }' Makefile | tr -s ' '
}
cut_short() { # cut_short: the entries on stdin that stop mid-sentence, one per line
    awk '{ o = gsub(/\(/, "("); c = gsub(/\)/, ")"); t = $0
        if (o != c || t ~ /[,;:(]$/ || t ~ / (and|or|the|of|a|an|to|with|from|into|under|for|in|on|by|at|as|also)$/) print }'
}
check_make_help_whole() {
    local help want got short
    help=$(make --no-print-directory help 2>&1)
    got=$(printf '%s\n' "$help" | help_entries)
    want=$(makefile_entries)
    short=$(printf '%s\n' "$got" | cut_short | cut -c1-60 | tr '\n' ';')
    if [ "$got" != "$want" ]; then
        not_ok make-help-whole "make help differs from the Makefile's entries: $(diff <(echo "$want") <(echo "$got") | grep '^[<>]' | head -n 2 | cut -c1-100 | tr '\n' ' ')"
    elif [ -n "$short" ]; then
        not_ok make-help-whole "entries that stop mid-sentence: $short"
    else
        ok "make-help-whole ($(printf '%s\n' "$got" | wc -l) entries, each whole)"
    fi
}
check_make_help_whole


# ---- docs/hacking.md against the code (issue 37) ----------------------------------------------

# rooms_of TREE_ROOT: "NAME FOLDER/" per room of TREE_ROOT/rooms.txt ("." as TREE_ROOT/).
rooms_of() {
    awk -v root="$1" '/^[ \t]*(#|$)/ || $1 == "+" { next }
        { print $1, ($2 == "." ? root "/" : root "/" $2 "/") }' "$1/rooms.txt"
}

# check_room_map TREE ROOT HEADING: the table under HEADING names ROOT's rooms and folders.
check_room_map() {
    local tree=$1 root=$2 heading=$3 got want
    want=$(rooms_of "$root")
    got=$(awk -v h="## $heading" '$0 == h { on = 1; next } /^## / { on = 0 }
        on && /^\| [a-z]+ \| `/ { f = $4; gsub(/`/, "", f); print $2, f }' docs/hacking.md)
    if [ "$got" = "$want" ]; then
        ok "rooms/$tree ($(wc -l <<<"$want") rooms, as $root/rooms.txt)"
    else
        not_ok "rooms/$tree" "the map under '$heading' is '$(tr '\n' ';' <<<"$got")', $root/rooms.txt says '$(tr '\n' ';' <<<"$want")'"
    fi
}

# room_of PATH: the room a path of src/ or platform/player/ lies in ("public" for include/sbfx.h),
# or nothing for a path outside them.
room_of() {
    local path=$1 root dir
    [ "$path" = include/sbfx.h ] && { echo public; return; }
    case $path in src/*) root=src ;; platform/player/*) root=platform/player ;; *) return ;; esac
    dir=$(dirname "$path")/
    [ -d "$path" ] && dir=${path%/}/
    rooms_of "$root" | awk -v d="$dir" '$2 == d { print $1 }'
}

# walkthrough_steps: one line per step of docs/hacking.md's "## Adding ..." sections:
# "TITLE<TAB>LINE<TAB>PATH[:ROOM] ...<TAB>NAME ..." (a step is a numbered item with its
# continuation lines).
walkthrough_steps() {
    awk -v OFS='\t' '
    function flush(   t, paths, names, s, span, after, room) {
        if (item == "") return
        paths = ""; names = ""; t = item
        while (match(t, /`[^`]+`/)) {
            span = substr(t, RSTART + 1, RLENGTH - 2); after = substr(t, RSTART + RLENGTH)
            t = after
            if (span ~ /\// || span ~ /\.(c|h|sh|glsl|frag|vert|md|txt|1)$/ || span == "Makefile") {
                room = ""
                if (match(after, /^ \([a-z]+\)/)) room = substr(after, 3, RLENGTH - 3)
                paths = paths (paths == "" ? "" : " ") span (room == "" ? "" : ":" room)
            } else if (span ~ /^[A-Za-z_][A-Za-z0-9_]*$/) {
                names = names (names == "" ? "" : " ") span
            }
        }
        print title, start, paths, names
        item = ""
    }
    /^## / { flush(); on = ($0 ~ /^## Adding /); title = substr($0, 4); next }
    !on { next }
    /^[0-9]+\. / { flush(); item = $0; start = NR; next }
    /^   [^ ]/ && item != "" { item = item " " substr($0, 4); next }
    { flush() }
    END { flush() }' docs/hacking.md
}

check_walkthroughs() {
    local title line paths names problems="" p path room want name found steps=0 current="" tname
    while IFS=$'\t' read -r title line paths names; do
        if [ "$title" != "$current" ]; then
            [ -n "$current" ] && report_walkthrough "$current" "$steps" "$problems"
            current=$title steps=0 problems=""
        fi
        steps=$((steps + 1))
        for p in $paths; do
            path=${p%%:*} room=""
            [ "$p" != "$path" ] && room=${p#*:}
            if [ ! -e "$path" ]; then problems="$problems; line $line: $path does not exist"; continue; fi
            want=$(room_of "$path")
            if [ -n "$room" ] && [ -n "$want" ] && [ "$room" != "$want" ]; then
                problems="$problems; line $line: $path is in the room $want, not $room"
            fi
        done
        for name in $names; do
            found=0
            for p in $paths; do
                path=${p%%:*}
                [ -e "$path" ] && grep -rqw -- "$name" "$path" && { found=1; break; }
            done
            [ "$found" -eq 1 ] || problems="$problems; line $line: $name occurs in none of $(sed 's/:[a-z]*//g' <<<"$paths")"
        done
    done < <(walkthrough_steps)
    [ -n "$current" ] && report_walkthrough "$current" "$steps" "$problems"
}

report_walkthrough() {
    local name
    name=$(tr 'A-Z ' 'a-z-' <<<"$1")
    if [ -z "$3" ]; then ok "walkthrough/$name ($2 steps)"; else not_ok "walkthrough/$name" "${3#; }"; fi
}

if [ -f docs/hacking.md ]; then
    check_room_map src src "The library's rooms"
    check_room_map player platform/player "The player's rooms"
    check_room_map net platform/net "The network's rooms"
    check_walkthroughs
fi

# README's Requirements name what tests/fresh/run.sh (make test-fresh) puts in the bare root
# before the quick start: the `apt-get install ...` line there is its REQUIREMENTS, word for word.
check_requirements() {
    local want said
    want=$(sed -n 's/^REQUIREMENTS="\(.*\)"$/\1/p' tests/fresh/run.sh)
    said=$(sed -n '/^## Requirements/,/^## /p' README.md | grep -o '`apt-get install [^`]*`' | head -n 1 | tr -d '`')
    if [ -n "$want" ] && [ "$said" = "apt-get install $want" ]; then
        ok "requirements (README: '$said'; make test-fresh's bare root has the same)"
    else
        not_ok requirements "README's Requirements say '$said', tests/fresh/run.sh installs '$want'"
    fi
}
check_requirements

files=$( { echo README.md; find docs -name '*.md' 2>/dev/null | sort; } )
for md in $files; do
    [ -f "$md" ] || continue
    md_scan "$md" >"$tmp/scan"
    check_links "$md" "$tmp/scan"
    check_examples "$md" "$tmp/scan"
done
[ "$failures" -eq 0 ]
