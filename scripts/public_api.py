#!/usr/bin/env python3
"""Lists the public API of the library from rustdoc's JSON, one item a line.

    python3 scripts/public_api.py target/doc/v2ref.json > crates/v2ref/public-api/default.txt

Each line is `KIND PATH`: every item a dependent crate can name, under every
path it can name it by (a type reachable by two paths is listed twice, so a
second path shows), with the public fields of structs, the variants of
enums, the methods and associated constants of inherent impls and the items
of traits. Trait impls are left out (their number follows the derives).
Items hidden from the docs (`#[doc(hidden)]`) are not in rustdoc's JSON and
so not here. Another crate's items re-exported (the facade `v2ref`
re-exports `v2ref-core`'s) are followed into that crate's JSON, given after
the first: each is listed with its members under the path it is re-exported
by, as if it were defined there. Only the standard library is used (json), so that the check
needs no package.

`--counts` prints, instead of the listing, how many lines there are of each
kind, how many of the modules' items (types, functions, constants; not
their members) are reached by more than one path, and how many such items
there are in all (the surface's size, each item once).
"""

import json
import sys
from collections import Counter


def kind_of(item):
    return next(iter(item["inner"]))


class Lister:
    def __init__(self, doc, lines=None, reached=None, dependencies=()):
        self.index = doc["index"]
        self.paths = doc["paths"]
        self.name = doc["index"][str(doc["root"])]["name"]
        self.lines = set() if lines is None else lines
        # (crate, item id) -> the paths a module's item (not a member) is listed under
        self.reached = {} if reached is None else reached
        # crate name -> (its lister, its items' ids by path)
        self.dependencies = {}
        for dep in dependencies:
            lister = Lister(dep, self.lines, self.reached)
            by_path = {
                tuple(entry["path"]): item_id
                for item_id, entry in dep["paths"].items()
                if entry.get("crate_id") == 0
            }
            self.dependencies[lister.name] = (lister, by_path)

    def external(self, item_id):
        """The lister and id of another crate's item that this crate names."""
        entry = self.paths.get(str(item_id))
        if entry is None or not entry["path"]:
            return None, None
        lister, by_path = self.dependencies.get(entry["path"][0], (None, None))
        if lister is None:
            return None, None
        dep_id = by_path.get(tuple(entry["path"]))
        return (lister, dep_id) if dep_id is not None else (None, None)

    def item(self, item_id):
        return self.index.get(str(item_id))

    def emit(self, kind, path, item_id):
        self.lines.add(f"{kind} {path}")

    def module(self, module_id, path, visiting):
        if module_id in visiting:  # a module re-exported into itself
            return
        visiting = visiting | {module_id}
        for child_id in self.item(module_id)["inner"]["module"]["items"]:
            child = self.item(child_id)
            if child is None or child["visibility"] != "public":
                continue
            if kind_of(child) == "use":
                self.reexport(child, path, visiting)
            else:
                self.named(child_id, child, f"{path}::{child['name']}", visiting)

    def reexport(self, use_item, path, visiting):
        use = use_item["inner"]["use"]
        target = self.item(use["id"]) if use["id"] is not None else None
        if target is None and use["id"] is not None:
            lister, dep_id = self.external(use["id"])
            if lister is not None:
                name = path if use["is_glob"] else f"{path}::{use['name']}"
                dep_item = lister.item(dep_id)
                if use["is_glob"] and kind_of(dep_item) == "module":
                    lister.module(dep_id, path, visiting)
                else:
                    lister.named(dep_id, dep_item, name, visiting)
                return
        if use["is_glob"]:
            if target is not None and kind_of(target) == "module":
                self.module(use["id"], path, visiting)
            elif target is not None and kind_of(target) == "enum":
                for variant_id in target["inner"]["enum"]["variants"]:
                    variant = self.item(variant_id)
                    self.emit("variant", f"{path}::{variant['name']}", variant_id)
            else:
                self.lines.add(f"use {path}::* = {use['source']}::*")
            return
        name = f"{path}::{use['name']}"
        if target is None:
            # Another crate's item, re-exported: listed by its source.
            self.lines.add(f"use {name} = {use['source']}")
        else:
            self.named(use["id"], target, name, visiting)

    def named(self, item_id, item, path, visiting):
        kind = kind_of(item)
        if kind != "module":
            self.reached.setdefault((self.name, str(item_id)), set()).add(path)
        if kind == "module":
            self.emit("mod", path, item_id)
            self.module(item_id, path, visiting)
        elif kind == "struct":
            self.emit("struct", path, item_id)
            struct_kind = item["inner"]["struct"]["kind"]
            fields = []
            if isinstance(struct_kind, dict) and "plain" in struct_kind:
                fields = struct_kind["plain"]["fields"]
            elif isinstance(struct_kind, dict) and "tuple" in struct_kind:
                fields = [f for f in struct_kind["tuple"] if f is not None]
            for field_id in fields:
                field = self.item(field_id)
                if field is not None and field["visibility"] == "public":
                    self.emit("field", f"{path}::{field['name']}", field_id)
            self.inherent(item["inner"]["struct"]["impls"], path)
        elif kind == "enum":
            self.emit("enum", path, item_id)
            for variant_id in item["inner"]["enum"]["variants"]:
                variant = self.item(variant_id)
                self.emit("variant", f"{path}::{variant['name']}", variant_id)
            self.inherent(item["inner"]["enum"]["impls"], path)
        elif kind == "trait":
            self.emit("trait", path, item_id)
            for member_id in item["inner"]["trait"]["items"]:
                member = self.item(member_id)
                self.emit(self.member_kind(member), f"{path}::{member['name']}", member_id)
        elif kind == "function":
            self.emit("fn", path, item_id)
        elif kind in ("constant", "static"):
            self.emit("const" if kind == "constant" else "static", path, item_id)
        elif kind == "type_alias":
            self.emit("type", path, item_id)
        elif kind in ("macro", "proc_macro"):
            self.emit("macro", path, item_id)
        else:
            self.emit(kind, path, item_id)

    @staticmethod
    def member_kind(member):
        kind = kind_of(member)
        return {"function": "fn", "assoc_const": "const", "assoc_type": "type"}.get(kind, kind)

    def inherent(self, impl_ids, path):
        for impl_id in impl_ids:
            impl = self.item(impl_id)
            if impl is None or impl["inner"]["impl"]["trait"] is not None:
                continue
            for member_id in impl["inner"]["impl"]["items"]:
                member = self.item(member_id)
                if member is not None and member["visibility"] == "public":
                    self.emit(self.member_kind(member), f"{path}::{member['name']}", member_id)


def main():
    args = sys.argv[1:]
    counts = "--counts" in args
    args = [a for a in args if a != "--counts"]
    if not args:
        sys.exit("usage: public_api.py [--counts] RUSTDOC_JSON [DEPENDENCY_RUSTDOC_JSON ...]")
    docs = []
    for arg in args:
        with open(arg, encoding="utf-8") as f:
            docs.append(json.load(f))
    lister = Lister(docs[0], dependencies=docs[1:])
    root = lister.item(docs[0]["root"])
    lister.module(docs[0]["root"], root["name"], frozenset())
    if counts:
        kinds = Counter(line.split(" ", 1)[0] for line in lister.lines)
        twice = sum(1 for paths in lister.reached.values() if len(paths) > 1)
        print(" ".join(f"{k} {kinds[k]}" for k in sorted(kinds)), f"| items on two or more paths {twice}",
              f"| module items {len(lister.reached)}")
    else:
        sys.stdout.write("".join(line + "\n" for line in sorted(lister.lines)))


if __name__ == "__main__":
    main()
