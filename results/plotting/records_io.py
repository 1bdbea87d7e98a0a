"""Reading a suite's records.jsonl (one JSON record per line) for the plotting scripts."""
import json


def load_records(path):
    """The records of one records.jsonl, in file order; blank lines skipped."""
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]
