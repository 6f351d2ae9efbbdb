// Validates Kubernetes manifests against the Kubernetes API schema with npm's
// kubernetes-models (the JSON schemas of the API's OpenAPI spec, checked by ajv), without an
// API server. Usage: node validate_k8s.mjs FILE.yaml... Every document must be a kind this
// script knows and pass its schema; a wrong type, a bad enum value or a missing required
// field fails. The schemas allow fields they do not name (the API server drops or, with
// strict field validation, refuses them), so a misspelt field would pass unseen: the
// document is validated through a Proxy that records which fields the schema's validators
// read, and a field no validator read is reported as unknown. Exit 0 when all pass, 1
// otherwise.
import { readFileSync } from "node:fs";
import yaml from "js-yaml";
import { Job } from "kubernetes-models/batch/v1";
import { PersistentVolumeClaim, ConfigMap } from "kubernetes-models/v1";

const kinds = { "batch/v1 Job": Job, "v1 PersistentVolumeClaim": PersistentVolumeClaim, "v1 ConfigMap": ConfigMap };
// `doc` behind proxies that note every (object, field) the validators read.
function watched(doc, seen) {
  const proxies = new WeakMap();
  const wrap = (o) => {
    if (o === null || typeof o !== "object") return o;
    if (!proxies.has(o)) {
      seen.set(o, new Set());
      proxies.set(o, new Proxy(o, {
        get(target, prop, receiver) {
          if (typeof prop === "string") seen.get(target).add(prop);
          return wrap(Reflect.get(target, prop, receiver));
        },
      }));
    }
    return proxies.get(o);
  };
  return wrap(doc);
}

// Paths of the fields of `o` that the validators never read.
function unread(o, seen, path, out) {
  if (o === null || typeof o !== "object") return out;
  const read = seen.get(o) ?? new Set();
  for (const [k, v] of Object.entries(o)) {
    const here = Array.isArray(o) ? `${path}[${k}]` : `${path}.${k}`;
    if (!Array.isArray(o) && !read.has(k)) out.push(here);
    else unread(v, seen, here, out);
  }
  return out;
}

let failures = 0, checked = 0;
for (const file of process.argv.slice(2)) {
  for (const doc of yaml.loadAll(readFileSync(file, "utf8"))) {
    if (!doc) continue;
    const kind = `${doc.apiVersion} ${doc.kind}`;
    const Model = kinds[kind];
    if (!Model) {
      console.error(`${file}: ${kind} (${doc.metadata?.name}): no schema known here`);
      failures++;
      continue;
    }
    try {
      const seen = new WeakMap();
      const model = new Model(doc);
      const data = JSON.parse(JSON.stringify(model));
      Model.prototype.validate.call(watched(data, seen));
      // Again on the model itself: the schema's own verdict, whatever the proxy changed.
      model.validate();
      const unknown = unread(data, seen, "", []);
      if (unknown.length) throw new Error(`unknown field(s): ${unknown.join(", ")}`);
      checked++;
      console.log(`${file}: ${kind} ${doc.metadata?.name}: valid`);
    } catch (e) {
      console.error(`${file}: ${kind} ${doc.metadata?.name}: ${e.message}`);
      failures++;
    }
  }
}
if (checked === 0 && failures === 0) { console.error("no manifests"); failures++; }
process.exit(failures ? 1 : 0);
