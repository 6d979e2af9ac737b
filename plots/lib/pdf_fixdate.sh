#!/usr/bin/env bash
# Sets the /CreationDate of PDFs written by gnuplot's pdfcairo terminal to
# SOURCE_DATE_EPOCH (default 0: 1970-01-01), so that a figure redrawn from
# the same data is byte-identical (cairo 1.16 stamps the current time and
# ignores SOURCE_DATE_EPOCH). The new date has the length of the old one
# (padded with spaces, which PDF ignores there), so the cross-reference
# offsets stay valid. Files without such a date are left as they are.
# Usage: plots/lib/pdf_fixdate.sh FILE.pdf...
set -euo pipefail
epoch=${SOURCE_DATE_EPOCH:-0}
if ! [[ "$epoch" =~ ^[0-9]+$ ]] || [ "${#epoch}" -gt 11 ]; then
  echo "pdf_fixdate: SOURCE_DATE_EPOCH must be whole seconds since 1970 (0 to 99999999999), got '$epoch'" >&2
  exit 2
fi
stamp=$(date -u -d "@$epoch" +%Y%m%d%H%M%S)
for f in "$@"; do
  STAMP=$stamp perl -0777 -pi -e '
    s{/CreationDate \(D:\d{14}(?:Z|[+-]\d\d\x27\d\d\x27?)?\)}{
      my ($old, $new) = ($&, "/CreationDate (D:$ENV{STAMP}Z)");
      length($new) <= length($old) ? $new . (" " x (length($old) - length($new))) : $old
    }ge' "$f"
done
