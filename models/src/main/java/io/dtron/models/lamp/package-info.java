/** The smart lamp of Uppaal TRON's manual: a system under test for TRON's {@code LightContr.xml}. */
package io.dtron.models.lamp;
