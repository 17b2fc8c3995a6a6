#!/usr/bin/env python3
"""The Markdown table of a real-files sweep (tools/real_files_sweep.sh).

    real_files_summary.py results.tsv > summary.md

Paths are shown relative to /usr/share; messages name the file by its base
name only. Folder names that are upstream bug-tracker references are left
out of the paths (the file names are enough).
"""
import csv
import os
import re
import sys


def short(path):
    p = path.replace('/usr/share/', '')
    return '/'.join('…' if re.match(r'(?i)issue', part) else part for part in p.split('/'))


def main():
    rows = list(csv.DictReader(open(sys.argv[1]), delimiter='\t', quoting=csv.QUOTE_NONE))
    ok = [r for r in rows if r['rc'] == '0']
    print(f"{len(rows)} files tried: {len(ok)} rendered, {len(rows) - len(ok)} refused with a message.\n")
    print("| file | exit | s | model coverage | first error or warning |")
    print("|---|--:|--:|--:|---|")
    for r in rows:
        folder = os.path.dirname(r['file']) + '/'
        msg = r['message'].replace('clpath: ', '').replace(folder, '')
        msg = re.sub(r'/usr/share/\S*/', '', msg).replace('|', '\\|')
        print(f"| {short(r['file'])} | {r['rc']} | {r['seconds']} | {r['coverage']} | {msg.strip()} |")


if __name__ == '__main__':
    main()
