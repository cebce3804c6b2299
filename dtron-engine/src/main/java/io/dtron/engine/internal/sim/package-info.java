/** How mutants of a model are made: copies of the network with one change each. Not API. */
package io.dtron.engine.internal.sim;
