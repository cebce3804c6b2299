/**
 * Delta-extended models (DTRON thesis, section 3.5): {@link io.dtron.model.delta.DeltaExtension} widens the clock
 * bounds of a model's observable edges by the delays measured between the tester and the system under test.
 */
package io.dtron.model.delta;
