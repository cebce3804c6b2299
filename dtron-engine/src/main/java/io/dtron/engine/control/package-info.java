/**
 * The model as controller ({@link io.dtron.engine.control.Controller}): the engine executes the controller part of a
 * closed model (the {@code i_} side, its commands) against a plant (its {@code o_} readings), raises an alarm when
 * the plant deviates from the model and then takes the model's safe action; and model versions checked and taken
 * at a reset point without stopping the run ({@link io.dtron.engine.control.ModelVersion}).
 */
package io.dtron.engine.control;
