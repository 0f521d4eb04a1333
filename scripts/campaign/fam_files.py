"""Family 2: damaged instrument files. Every topography file of the data folders, mutated
(truncated, bytes flipped in header and body, single bits flipped in the header's first 4 KiB
where the size and scale fields lie, 256 header bytes zeroed, a header spliced onto another
file's body, declared sizes inflated, a height set to 1e308; x3p: XML edits, checksums broken),
then `asperity inspect`; a sampled part also runs a one-node surface study reading the file.

A header mutation that `inspect` reads as valid although its grid, spacing or Sq differ from the
unmutated file's is flagged `accepted_corrupt` (a silently wrong number: the reader should have
refused the damaged header), with the change in the notes."""

import io
import os
import re
import shutil
import zipfile

from common import HEIGHT_MAX, NONFINITE_WORD, Case, classify_run, message_flags, process_outcome, rejection

SKIP = re.compile(r"(\.md|\.json|\.py|LICENSE|Licen[cs]e|GPL)", re.I)
HEIGHT_LINE = re.compile(r"\b(Sq|Sa|Sz|Sp|Sv)\b[^=\n]*=\s*([-+\d.eE]+|inf|NaN)\s*(\w+)?")
# What a header mutation must not change silently: the grid, the spacing and Sq as inspect
# prints them.
READ_VALUES = re.compile(r"^(grid:.*|spacing:.*|points:.*|length:.*|\s*Sq\s*=.*|Rq .*)$", re.M)
# Names of the mutations that damage the header (see header_mutations and generic_mutations).
HEADER_MUTATION = re.compile(r"(byte flips in the header|header bit|header bytes .* zeroed)")


def data_files(folders):
    out = []
    for folder in folders:
        for root, dirs, files in os.walk(folder):
            dirs[:] = [d for d in dirs if d != "LICENSES"]
            out += [os.path.join(root, f) for f in files if not SKIP.search(f)]
    return sorted(out)


def flip(data, rng, lo, hi, count):
    b = bytearray(data)
    hi = min(hi, len(b))
    if hi <= lo:
        return bytes(b)
    for _ in range(count):
        i = rng.randrange(lo, hi)
        b[i] ^= 1 << rng.randrange(8)
    return bytes(b)


def inflate_text_number(data, rng):
    """A decimal integer of the first 4 KiB multiplied by 10^4 (a declared size, perhaps)."""
    head = data[:4096]
    spots = [m for m in re.finditer(rb"(?<![\d.])\d{2,5}(?![\d.])", head)]
    if not spots:
        return None
    m = rng.choice(spots)
    return data[: m.start()] + m.group() + b"0000" + data[m.end() :]


def inflate_binary_word(data, rng):
    """A little-endian u32 of the first 1 KiB in [16, 65536] set to 0x7fffffff."""
    spots = [i for i in range(0, min(1024, len(data)) - 3, 2)
             if 16 <= int.from_bytes(data[i : i + 4], "little") <= 65536]
    if not spots:
        return None
    i = rng.choice(spots)
    return data[:i] + (0x7FFFFFFF).to_bytes(4, "little") + data[i + 4 :]


def huge_height(data, rng):
    """For text files: one number of the body replaced by 1e308."""
    spots = list(re.finditer(rb"-?\d+\.\d+(?:[eE][-+]?\d+)?", data))
    if len(spots) < 10:
        return None
    m = rng.choice(spots[len(spots) // 2 :])
    return data[: m.start()] + b"1e308" + data[m.end() :]


def header_mutations(data, rng):
    """(name, bytes): single bits flipped in the first 4 KiB (where size and scale fields lie,
    e.g. an NMS file's nx and ny at byte 1368) and 256 header bytes zeroed."""
    n = len(data)
    out = []
    for _ in range(3):
        i = rng.randrange(min(4096, max(1, n // 4)))
        bit = rng.randrange(8)
        b = bytearray(data)
        b[i] ^= 1 << bit
        out.append((f"header bit {bit} of byte {i} flipped", bytes(b)))
    for start in (0, 256):
        if n >= start + 512:
            out.append((f"header bytes {start}-{start + 255} zeroed",
                        data[:start] + bytes(256) + data[start + 256:]))
    return out


def read_values(stdout):
    """The grid, spacing and Sq lines `inspect` printed (the values a header mutation must not
    change silently)."""
    return [m.group(1).strip() for m in READ_VALUES.finditer(stdout)]


def differs(before, after):
    """Two lines of read_values: an Sq/Rq line differs beyond 0.1 %, any other at all."""
    numbers = [re.search(r"=\s*([-+\d.eE]+)", line) for line in (before, after)]
    if before.lstrip().startswith(("Sq", "Rq")) and all(numbers):
        try:
            b, a = (float(m.group(1)) for m in numbers)
        except ValueError:
            return before != after
        return abs(a - b) > 1e-3 * abs(b)
    return before != after


def generic_mutations(path, data, others, rng):
    """(name, bytes) for any file."""
    n = len(data)
    out = []
    for frac in sorted(rng.random() for _ in range(3)):
        cut = max(1, int(n * frac))
        out.append((f"truncated at {cut}/{n}", data[:cut]))
    out.append(("truncated to 0 bytes", b""))
    for k in (1, 8):
        out.append((f"{k} byte flips in the header", flip(data, rng, 0, 512, k)))
        out.append((f"{k} byte flips in the body", flip(data, rng, n // 4, n, k)))
    other = rng.choice(others)
    with open(other, "rb") as f:
        body = f.read()
    h = min(n, max(64, n // 20), 8192)
    out.append((f"header ({h} B) spliced onto {os.path.basename(other)}'s body", data[:h] + body[h:]))
    out += header_mutations(data, rng)
    for name, f in (("declared size inflated (text)", inflate_text_number),
                    ("declared size inflated (binary)", inflate_binary_word),
                    ("one height 1e308", huge_height)):
        m = f(data, rng)
        if m is not None:
            out.append((name, m))
    return out


def has_binary_payload(path):
    """An x3p with main.xml and a bindata/ payload (not a DataList in the XML)."""
    try:
        names = zipfile.ZipFile(path).namelist()
    except (OSError, zipfile.BadZipFile):
        return False
    return "main.xml" in names and any(n.startswith("bindata/") for n in names)


def x3p_zero_payload(data, side=16384):
    """An x3p declaring side² doubles with a zero-filled payload (a 2 GiB entry, 2 MiB zipped),
    built only when its case runs."""

    def build():
        z = zipfile.ZipFile(io.BytesIO(data))
        xml = z.read("main.xml").decode("utf-8", "replace")
        xml = re.sub(r"<Size([XY])>\d+<", rf"<Size\g<1>>{side}<", xml)
        xml = re.sub(r"(<CZ>.*?<DataType>)\w(</DataType>)", r"\g<1>D\2", xml, flags=re.S)
        xml = re.sub(r"<MD5ChecksumPointData>[^<]*</MD5ChecksumPointData>", "", xml)
        link = re.search(r"<PointDataLink>([^<]*)<", xml)
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED, compresslevel=1) as w:
            w.writestr("main.xml", xml)
            with w.open(link.group(1) if link else "bindata/data.bin", "w", force_zip64=True) as f:
                chunk = bytes(1 << 22)
                for _ in range(side * side * 8 // len(chunk)):
                    f.write(chunk)
        return buf.getvalue()

    return build


def x3p_mutations(data, rng):
    """(name, bytes) for an x3p (zip) file: XML and checksum damage."""
    try:
        z = zipfile.ZipFile(io.BytesIO(data))
        parts = {n: z.read(n) for n in z.namelist()}
    except Exception:
        return []
    xml = parts.get("main.xml", b"").decode("utf-8", "replace")
    bin_name = next((n for n in parts if n.startswith("bindata/")), None)
    out = []

    def rezip(name, **changes):
        p = dict(parts, **{k.replace("__", "/").replace("_DOT_", "."): v for k, v in changes.items()})
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as w:
            for k, v in p.items():
                w.writestr(k, v)
        out.append((name, buf.getvalue()))

    def sub(pattern, repl):
        return re.sub(pattern, repl, xml, count=1).encode()

    rezip("Increment 1e308", main_DOT_xml=sub(r"<Increment>[^<]*<", "<Increment>1e308<"))
    rezip("Increment 0", main_DOT_xml=sub(r"<Increment>[^<]*<", "<Increment>0<"))
    rezip("Increment NaN", main_DOT_xml=sub(r"<Increment>[^<]*<", "<Increment>NaN<"))
    rezip("SizeX 16384, SizeY 16384", main_DOT_xml=re.sub(r"<Size([XY])>\d+<", r"<Size\g<1>>16384<", xml).encode())
    rezip("SizeX 2^40", main_DOT_xml=sub(r"<SizeX>\d+<", "<SizeX>1099511627776<"))
    nest = "<a>" * 50000 + "</a>" * 50000
    rezip("50 000 nested elements", main_DOT_xml=xml.replace("<Record2>", "<Record2>" + nest, 1).encode())
    rezip("MD5ChecksumPointData wrong (data intact)",
          main_DOT_xml=sub(r"<MD5ChecksumPointData>[^<]*<", "<MD5ChecksumPointData>" + "0" * 32 + "<"))
    if "md5checksum.hex" in parts:
        rezip("md5checksum.hex wrong", md5checksum_DOT_hex=b"0" * 32 + b" *main.xml\n")
    if bin_name and parts[bin_name]:
        key = bin_name.replace("/", "__").replace(".", "_DOT_")
        b = parts[bin_name]
        rezip("point data flipped (checksum not updated)", **{key: flip(b, rng, len(b) // 2, len(b), 4)})
        rezip("point data truncated", **{key: b[: len(b) // 2]})
    return out


class FileFamily:
    name = "files"

    def __init__(self, ctx):
        self.ctx = ctx
        self.dir = os.path.join(ctx.scratch, "files")
        os.makedirs(self.dir, exist_ok=True)
        self.cache = os.path.join(self.dir, "cache")
        self.rng = ctx.rng("files")
        self.files = data_files(ctx.data_dirs)
        self.baseline = {}  # path -> read_values of the unmutated file
        self.cases = self.build()

    def build(self):
        x3ps = [p for p in self.files if p.endswith(".x3p") and has_binary_payload(p)]
        special = [(None, "FIFO as topography file", "fifo", False),
                   (None, "/dev/zero as topography file", "/dev/zero", False)]
        if x3ps:
            smallest = min(x3ps, key=os.path.getsize)
            with open(smallest, "rb") as f:
                special.append((smallest, "16384² points declared, zero-filled payload",
                                x3p_zero_payload(f.read()), False))
        per_file = []
        for path in self.files:
            with open(path, "rb") as f:
                data = f.read()
            others = [o for o in self.files if o != path]
            muts = generic_mutations(path, data, others, self.rng)
            if path.endswith(".x3p"):
                muts += x3p_mutations(data, self.rng)
            cases = [(path, name, m, self.rng.random() < 0.5) for name, m in muts]
            self.rng.shuffle(cases)
            per_file.append(cases)
        order = special
        while any(per_file):
            for cases in per_file:
                if cases:
                    order.append(cases.pop())
        return order

    def __iter__(self):
        unknown = set()
        for path in self.files:  # unmutated: the rules must pass on what the readers accept
            with open(path, "rb") as f:
                case = self.run_case(path, "unmutated", f.read(), True)
            case.family = "baselines"
            if case.outcome == "ok":
                self.baseline[path] = read_values(case.procs[0].stdout)
            if "unknown topography format" in case.procs[0].stderr:
                unknown.add(path)  # its mutations would all end there
            yield case
        for path, name, data, with_study in self.cases:
            if path not in unknown:
                yield self.run_case(path, name, data, with_study)

    def run_case(self, path, name, data, with_study):
        ctx = self.ctx
        rel = os.path.relpath(path, os.path.dirname(os.path.dirname(path))) if path else "special"
        case = Case(self.name, f"{rel}: {name}")
        base = os.path.basename(path) if path else "topography.dat"
        target = os.path.join(self.dir, base)
        for leftover in os.listdir(self.dir):
            if leftover not in ("cache",):
                p = os.path.join(self.dir, leftover)
                shutil.rmtree(p) if os.path.isdir(p) and not os.path.islink(p) else os.remove(p)
        if callable(data):
            data = data()
        if data == "fifo":
            os.mkfifo(target)
            case.inputs["how.txt"] = f"{base} is a FIFO (mkfifo)\n".encode()
        elif isinstance(data, str):
            os.symlink(data, target)
            case.inputs[base] = data
        else:
            with open(target, "wb") as f:
                f.write(data)
            case.inputs[base] = data
        p = ctx.runner.run([ctx.bin, "inspect", base], self.dir)
        case.procs.append(p)
        case.flags |= message_flags([p.stderr])
        special = process_outcome(p)
        if special:
            case.outcome = special
            return case
        if p.rc != 0:
            case.outcome = rejection(p)
            if not p.stderr.strip():
                case.flags.add("no_message")
            return case
        case.outcome = "ok"
        if NONFINITE_WORD.search(p.stdout):
            case.flags.add("nonfinite_printed")
        for m in HEIGHT_LINE.finditer(p.stdout):
            value = m.group(2)
            try:
                if abs(float(value)) > HEIGHT_MAX and (m.group(3) or "") == "m":
                    case.flags.add("impossible_ok")
                    case.notes.append(f"inspect printed {m.group(0).strip()}")
            except ValueError:
                pass
        if "checksum" in name.lower() or "point data flipped" in name:
            case.flags.add("accepted_corrupt")
            case.notes.append("inspect read a file whose checksum does not match")
        self.compare_with_baseline(case, path, name, p.stdout)
        if with_study:
            self.surface_study(case, base, p.stdout)
        return case

    def compare_with_baseline(self, case, path, name, stdout):
        """Flags a header mutation read as valid with another grid or spacing than the
        unmutated file's, or an Sq (Rq) more than 0.1 % away: a flipped bit in a data value
        that happens to lie in the first bytes moves Sq far less."""
        before = self.baseline.get(path)
        if before is None or not HEADER_MUTATION.search(name):
            return
        after = read_values(stdout)
        changed = [f"{b!r} -> {a!r}" for b, a in zip(before, after) if differs(b, a)]
        if len(before) != len(after):
            changed.append(f"{len(before)} values printed -> {len(after)}")
        if changed:
            case.flags.add("accepted_corrupt")
            case.notes.append("header damage read as valid: " + "; ".join(changed[:3]))

    def surface_study(self, case, base, inspect_out):
        ctx = self.ctx
        spacing = ""
        if re.search(r"^spacing:\s+not in the file", inspect_out, re.M):
            spacing = "        pixel_size: 1 um\n"
        study = (
            "study: damaged-file\nnodes:\n  s:\n    surface:\n      file:\n"
            f"        path: {base}\n{spacing}"
        ).encode()
        with open(os.path.join(self.dir, "case.yaml"), "wb") as f:
            f.write(study)
        case.inputs["case.yaml"] = study
        out = os.path.join(self.dir, "out")
        r = ctx.runner.run([ctx.bin, "run", "case.yaml", "--out", "out", "--cache", "cache", "-q"], self.dir)
        classify_run(case, r, out, validated=False)
