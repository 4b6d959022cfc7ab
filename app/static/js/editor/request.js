// An operation's request body from the editor: the wing, the flight, the solver options, and
// what a loaded body keeps as given that this operation's body takes (its schema says which).

import { takes } from "../schema.js";
import { state } from "../state.js";
import { flight } from "./flight.js";
import { withChordwise } from "./surfaces.js";
import { sparOptions, wing } from "./wing.js";

/** The body of `operation` ("solve", "roll"...): wing, flight (its airspeed `withVelocity`),
 * options (those loaded, as given; the spar's safety factor; the surfaces' chordwise panels)
 * and the loaded body's other keys that `operation`'s body has (a solve's initial_guess). */
export function editorRequest(operation, { withVelocity }) {
  const request = { wing: wing(), flight: flight(operation, { withVelocity }) };
  const options = sparOptions(Object.keys(state.options).length ? { ...state.options } : undefined);
  if (options) request.options = options;
  withChordwise(request);
  for (const [key, v] of Object.entries(state.kept)) {
    if (!(key in request) && takes(operation, key)) request[key] = v;
  }
  return request;
}
