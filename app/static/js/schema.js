// The running API's OpenAPI document (read once as the page opens): which schemas this API
// version has, and what each operation's request body takes, so that the page offers only what
// the service accepts and sends a loaded body's parts only to operations that take them.

import * as api from "./api.js";

let document_ = null;

/** Read /openapi.json (null when it cannot be had: then no optional part is offered). */
export async function readDocument() {
  document_ = await api.openapi();
  return document_;
}

/** components.schemas of the running API ({} before it is read). */
export const schemas = () => document_?.components?.schemas ?? {};

/** The schema a node names ($ref), followed. */
export function resolve(node) {
  let seen = 0;
  while (node?.$ref && seen++ < 20) node = schemas()[node.$ref.split("/").at(-1)];
  return node ?? null;
}

/** The object schemas a node may be: its oneOf/anyOf members, each resolved (null left out). */
export function variants(node) {
  const resolved = resolve(node);
  if (!resolved) return [];
  const members = resolved.oneOf ?? resolved.anyOf;
  if (members) return members.flatMap(variants);
  return resolved.type === "null" ? [] : [resolved];
}

/** The request body schema of `operation` (a POST /jobs operation: "solve", "batch"), or null. */
export function requestSchema(operation) {
  const submission = document_?.paths?.["/jobs"]?.post?.requestBody?.content?.["application/json"]?.schema;
  for (const member of variants(submission)) {
    const name = member.properties?.operation;
    if (name?.const === operation || (name?.enum?.length === 1 && name.enum[0] === operation)) {
      return resolve(member.properties.request);
    }
  }
  return null;
}

/** Whether `operation`'s body has the top-level key `key`. */
export function takes(operation, key) {
  return variants(requestSchema(operation)).some((v) => key in (v.properties ?? {}));
}

/** Whether `operation`'s flight, given the way `way` ("alpha", "weight", "lift"), takes `key`. */
export function flightTakes(operation, way, key) {
  const flights = variants(requestSchema(operation)).flatMap((v) => variants(v.properties?.flight));
  return flights.some((v) => way in (v.properties ?? {}) && key in v.properties);
}

/** The default of `operation`'s body at `path` (["options", "safety_factor"]), or undefined. */
export function defaultAt(operation, path) {
  let nodes = [requestSchema(operation)];
  for (const key of path) nodes = nodes.flatMap(variants).map((v) => v.properties?.[key]).filter(Boolean);
  return nodes.map((n) => n.default ?? resolve(n)?.default).find((d) => d !== undefined);
}

/** The operations POST /jobs runs (its body's `operation` constants), in the document's order. */
export function jobOperations() {
  const submission = document_?.paths?.["/jobs"]?.post?.requestBody?.content?.["application/json"]?.schema;
  return variants(submission)
    .map((member) => member.properties?.operation)
    .map((name) => name?.const ?? (name?.enum?.length === 1 ? name.enum[0] : null))
    .filter(Boolean);
}

/** The top-level keys of `operation`'s body (every member's). */
export const requestKeys = (operation) => [...new Set(variants(requestSchema(operation)).flatMap((v) => Object.keys(v.properties ?? {})))];

/** POST /<operation>'s summary in the document, or null. */
export const summaryOf = (operation) => document_?.paths?.[`/${operation}`]?.post?.summary ?? null;
