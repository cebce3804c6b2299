/**
 * The street-light sample, after DTRON's case study of the street lights of Tartu: a small web application to
 * switch street-light controllers ({@link io.dtron.models.streetlight.StreetLightServer}), virtual controllers
 * that poll it, the model of its operators ({@link io.dtron.models.streetlight.StreetLightModel}) and
 * {@link io.dtron.models.streetlight.StreetLightWebTest}, which starts the application and its Selenium adapters
 * on a bus.
 */
package io.dtron.models.streetlight;
