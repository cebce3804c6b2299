/**
 * The Selenium adapters of the street-light model, one per input ({@code Login} serves {@code i_login}, ...),
 * with their locators and settings in {@code adapters.properties} beside them. Each runs in the browser of the
 * operator its input names and answers with {@code o_result}: {@code Check} reports the result page as its own
 * code, the others the automatic one.
 */
package io.dtron.models.streetlight.adapters;
